"""fit against `splinecal fit` on the bundled EuRoC excerpt, and simulate -> fit."""
import numpy as np
import pytest

import splinecal
from conftest import (EUROC, assert_same, load_yaml, quaternion_to_matrix, read_csv_columns,
                      run_tool, tool_error)

# The same C++ solve on the same inputs: only thread scheduling could differ (one thread here).
TOLERANCE = 1e-9


def test_fit_equals_the_command_line(tmp_path):
    args = dict(imu_yaml=str(EUROC / "sensor.yaml"), knot_spacing=0.05)
    run_tool("fit", "--imu", EUROC / "imu0.csv", "--poses", EUROC / "groundtruth.csv",
             "--imu-yaml", args["imu_yaml"], "--knot-spacing", 0.05, "--out", tmp_path)
    expected = load_yaml(tmp_path / "result.yaml")
    result = splinecal.fit(str(EUROC / "imu0.csv"), EUROC / "groundtruth.csv", **args)
    spline = result.pop("se3_spline")
    residuals = result.pop("imu_residuals")
    for timing in ("solve_time_s", "covariance_time_s"):  # wall times differ from run to run
        result[timing] = expected[timing]
    assert_same(result, expected, tol=TOLERANCE)
    t_ns, control = read_csv_columns(tmp_path / "spline.csv")
    np.testing.assert_allclose(spline.control_poses[:, :3, 3], control[:, :3], rtol=0,
                               atol=TOLERANCE)
    assert residuals["gyro_measured"].shape == (result["num_imu_samples"], 3)


def test_fit_of_arrays_equals_fit_of_files():
    t_ns, imu = read_csv_columns(EUROC / "imu0.csv")
    from_files = splinecal.fit(EUROC / "imu0.csv", EUROC / "groundtruth.csv", knot_spacing=0.05)
    from_arrays = splinecal.fit({"t_ns": t_ns, "gyro": imu[:, :3], "accel": imu[:, 3:]},
                                ground_truth_dict(EUROC / "groundtruth.csv"), knot_spacing=0.05)
    for key in ("gyro_bias", "accel_bias", "gravity_w"):
        np.testing.assert_allclose(from_arrays[key], from_files[key], rtol=0, atol=TOLERANCE)


def ground_truth_dict(path):
    """EuRoC ground truth as {t_ns, T_w_s}: p xyz, q wxyz in its columns 1..7."""
    t_ns, columns = read_csv_columns(path)
    T = np.tile(np.eye(4), (len(t_ns), 1, 1))
    T[:, :3, :3] = quaternion_to_matrix(columns[:, 3:7] /
                                        np.linalg.norm(columns[:, 3:7], axis=1)[:, None])
    T[:, :3, 3] = columns[:, 0:3]
    return {"t_ns": t_ns, "T_w_s": T}


@pytest.mark.parametrize("trajectory", ["se3", "split"])
def test_simulate_then_fit_recovers_the_biases(trajectory):
    gyro_bias, accel_bias = [0.01, -0.02, 0.015], [0.1, -0.05, 0.08]
    sim = splinecal.simulate(trajectory="vio_course", duration=10, seed=5,
                             gyro_bias=gyro_bias, accel_bias=accel_bias)
    assert sim["imu"]["gyro"].shape == (len(sim["imu"]["t_ns"]), 3)
    fit = splinecal.fit(sim["imu"], sim["ground_truth"], imu_yaml=None, trajectory=trajectory)
    assert fit["trajectory"] == trajectory
    assert fit["se3_spline"].trajectory == trajectory
    # 10 s of ADIS16448 noise: the accelerometer bias is weakly separated from gravity
    # (docs/fit.md); the tolerances are loose, the point is the pipeline.
    np.testing.assert_allclose(fit["gyro_bias"], gyro_bias, atol=2e-3)
    np.testing.assert_allclose(fit["accel_bias"], accel_bias, atol=3e-2)


def test_simulate_equals_the_command_line(tmp_path):
    run_tool("simulate", "--trajectory", "random", "--duration", 3, "--seed", 4, "--out", tmp_path)
    expected = load_yaml(tmp_path / "result.yaml")
    sim = splinecal.simulate(trajectory="random", duration=3, seed=4)
    t_ns, imu = read_csv_columns(tmp_path / "mav0/imu0/data.csv")
    np.testing.assert_array_equal(sim["imu"]["t_ns"], t_ns)
    np.testing.assert_allclose(sim["imu"]["gyro"], imu[:, :3], rtol=0, atol=1e-15)
    np.testing.assert_allclose(sim["imu"]["accel"], imu[:, 3:], rtol=0, atol=1e-15)
    for key in ("imu", "ground_truth", "se3_spline"):
        sim.pop(key)
    assert_same(sim, expected, tol=1e-12)


def test_an_imu_dict_in_g_is_refused_as_the_command_refuses_the_file(tmp_path):
    t_ns, imu = read_csv_columns(EUROC / "imu0.csv")
    imu[:, 3:] /= 9.80665
    path = tmp_path / "imu_in_g.csv"
    np.savetxt(path, np.column_stack([t_ns.astype(object), imu]), fmt="%s", delimiter=",")
    message = tool_error("fit", "--imu", path, "--poses", EUROC / "groundtruth.csv",
                         "--out", tmp_path / "o")
    with pytest.raises(splinecal.Error) as error:
        splinecal.fit({"t_ns": t_ns, "gyro": imu[:, :3], "accel": imu[:, 3:]},
                      EUROC / "groundtruth.csv")
    assert "looks like units of g" in str(error.value)
    assert message.split(f"{path}:", 1)[1] == str(error.value).split("imu:", 1)[1]
