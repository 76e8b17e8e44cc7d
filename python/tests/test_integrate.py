"""integrate against `splinecal integrate` on the bundled EuRoC excerpt, and on simulate's
arrays."""
import numpy as np
import pytest

import splinecal
from conftest import EUROC, assert_same, assert_same_files, load_yaml, run_tool, tool_error

FILES = ("result.yaml", "trajectory_euler.csv", "trajectory_midpoint.csv", "trajectory_rk4.csv",
         "trajectory.svg")


def test_integrate_writes_the_command_s_files(tmp_path):
    run_tool("integrate", "--imu", EUROC / "imu0.csv", "--groundtruth", EUROC / "groundtruth.csv",
             "--start", 2, "--duration", 5, "--out", tmp_path / "cli")
    result = splinecal.integrate(EUROC / "imu0.csv", EUROC / "groundtruth.csv", start=2,
                                 duration=5, out=tmp_path / "py")
    assert_same_files(tmp_path / "py", tmp_path / "cli", FILES)
    assert_same(result, load_yaml(tmp_path / "cli" / "result.yaml"), tol=0)
    assert set(result) >= {"euler", "midpoint", "rk4", "start_t_ns", "end_t_ns"}


def test_integrate_refuses_a_start_outside_the_data_as_the_command_does(tmp_path):
    message = tool_error("integrate", "--imu", EUROC / "imu0.csv", "--groundtruth",
                         EUROC / "groundtruth.csv", "--start", 100, "--out", tmp_path)
    with pytest.raises(splinecal.Error) as error:
        splinecal.integrate(EUROC / "imu0.csv", EUROC / "groundtruth.csv", start=100)
    assert message == "splinecal integrate: " + str(error.value)


def test_integrate_of_simulated_arrays():
    sim = splinecal.simulate(trajectory="vio_course", duration=5, noise_free=True, seed=3)
    result = splinecal.integrate(sim["imu"], sim["ground_truth"], method=["midpoint", "rk4"])
    assert set(result) & {"euler", "midpoint", "rk4"} == {"midpoint", "rk4"}
    # Noise-free readings of the spline at 200 Hz: the drift is the integrator's alone. Measured
    # after 5 s: midpoint 1.07e-4 m, rk4 7.7e-5 m; the bound is ~10x. Dead reckoning of the
    # EuRoC excerpt's real readings drifts 0.76 m in 5 s (docs/python.md), so a wrong state,
    # unit or frame would fail by orders of magnitude.
    for method in ("midpoint", "rk4"):
        error = result[method]["final_position_error_m"]
        assert error < 1e-3, f"{method}: {error} m after 5 s"
