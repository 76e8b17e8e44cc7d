"""SE3Spline against `splinecal evaluate` and `splinecal simulate --noise-free`."""
import numpy as np
import pytest

import splinecal
from conftest import DATA, quaternion_to_matrix, read_csv_columns, run_tool

# Both sides evaluate the same C++ code on the same control poses and print 17 digits; what is
# left is the quaternion-to-matrix conversion done here in numpy (a few ulps).
TOLERANCE = 1e-12
SPLINE_CSV = DATA / "vio_course_spline.csv"


def test_evaluate_equals_the_command_line(tmp_path):
    run_tool("evaluate", "--spline", SPLINE_CSV, "--every", 0.01, "--out", tmp_path)
    t_ns, columns = read_csv_columns(tmp_path / "evaluation.csv")
    spline = splinecal.SE3Spline.read_csv(SPLINE_CSV)
    e = spline.evaluate(t_ns)
    assert e["T_w_s"].shape == (len(t_ns), 4, 4)
    np.testing.assert_allclose(e["T_w_s"][:, :3, 3], columns[:, 0:3], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(e["T_w_s"][:, :3, :3], quaternion_to_matrix(columns[:, 3:7]),
                               rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(e["w_s"], columns[:, 7:10], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(e["v_w"], columns[:, 10:13], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(e["a_w"], columns[:, 13:16], rtol=0, atol=TOLERANCE)
    gyro, accel = spline.predict_imu(t_ns)
    np.testing.assert_allclose(gyro, columns[:, 16:19], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(accel, columns[:, 19:22], rtol=0, atol=TOLERANCE)


def test_predict_imu_equals_simulate_noise_free(tmp_path):
    run_tool("simulate", "--trajectory", "figure8", "--duration", 5, "--noise-free",
             "--gravity", 9.8, "--out", tmp_path)
    t_ns, imu = read_csv_columns(tmp_path / "mav0/imu0/data.csv")
    spline = splinecal.SE3Spline.read_csv(tmp_path / "spline.csv")
    gyro, accel = spline.predict_imu(t_ns, gravity=9.8)
    np.testing.assert_allclose(gyro, imu[:, 0:3], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(accel, imu[:, 3:6], rtol=0, atol=TOLERANCE)


def test_constructor_and_csv_round_trip(tmp_path):
    spline = splinecal.SE3Spline.read_csv(SPLINE_CSV)
    copy = splinecal.SE3Spline(spline.control_poses, spline.t0_ns, spline.dt_ns)
    assert copy.valid_range_ns() == spline.valid_range_ns()
    start, end = spline.valid_range_ns()
    t_ns = np.linspace(start, end, 101).astype(np.int64)
    # Through 4x4 matrices: the quaternions come back within rounding.
    np.testing.assert_allclose(copy.evaluate(t_ns)["T_w_s"], spline.evaluate(t_ns)["T_w_s"],
                               rtol=0, atol=1e-14)
    copy.write_csv(tmp_path / "copy.csv")
    again = splinecal.SE3Spline.read_csv(tmp_path / "copy.csv")
    np.testing.assert_array_equal(again.control_poses, copy.control_poses)  # 17 digits
    assert (again.t0_ns, again.dt_ns) == (copy.t0_ns, copy.dt_ns)


def test_valid_range_ends_evaluate_and_outside_is_refused():
    spline = splinecal.SE3Spline.read_csv(SPLINE_CSV)
    start, end = spline.valid_range_ns()
    assert start == spline.t0_ns + spline.dt_ns
    assert end == spline.t0_ns + (spline.num_control_poses - 2) * spline.dt_ns
    assert spline.evaluate(end)["T_w_s"].shape == (1, 4, 4)
    with pytest.raises(splinecal.Error, match="outside the valid range"):
        spline.evaluate([start, end + 1])
    assert issubclass(splinecal.Error, ValueError)


def test_split_trajectory_survives_the_csv_and_equals_the_command_line(tmp_path):
    coupled = splinecal.SE3Spline.read_csv(SPLINE_CSV)
    assert coupled.trajectory == "se3"  # a file without the key
    split = splinecal.SE3Spline(coupled.control_poses, coupled.t0_ns, coupled.dt_ns,
                                trajectory="split")
    assert split.trajectory == "split"
    split.write_csv(tmp_path / "split.csv")
    again = splinecal.SE3Spline.read_csv(tmp_path / "split.csv")
    assert again.trajectory == "split"
    run_tool("evaluate", "--spline", tmp_path / "split.csv", "--every", 0.05, "--out",
             tmp_path / "out")
    t_ns, columns = read_csv_columns(tmp_path / "out/evaluation.csv")
    e = again.evaluate(t_ns)
    np.testing.assert_allclose(e["T_w_s"][:, :3, 3], columns[:, 0:3], rtol=0, atol=TOLERANCE)
    np.testing.assert_allclose(e["a_w"], columns[:, 13:16], rtol=0, atol=TOLERANCE)
    # The same orientation as the coupled spline, another position.
    c = coupled.evaluate(t_ns)
    np.testing.assert_allclose(e["T_w_s"][:, :3, :3], c["T_w_s"][:, :3, :3], rtol=0, atol=1e-14)
    assert np.abs(e["T_w_s"][:, :3, 3] - c["T_w_s"][:, :3, 3]).max() > 1e-6
