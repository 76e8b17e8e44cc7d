"""calibrate against `splinecal calibrate` on a short simulated AprilGrid recording."""
import numpy as np

import splinecal
from conftest import DATA, assert_same, load_yaml, run_tool

CALIBRATION = DATA / "calibration"
# The same C++ solve on the same files, one thread: only wall times differ.
TOLERANCE = 1e-9
WALL_TIMES = ("initialisation_time_s", "solve_time_s", "covariance_time_s")


def test_calibrate_equals_the_command_line(tmp_path):
    sim = tmp_path / "sim"
    run_tool("simulate", "--trajectory", "calibration", "--duration", 5,
             "--camchain", CALIBRATION / "camchain_truth.yaml",
             "--target", CALIBRATION / "aprilgrid.yaml", "--seed", 2, "--out", sim)
    inputs = dict(imu=sim / "mav0/imu0/data.csv", observations=sim / "observations.csv",
                  camchain=CALIBRATION / "camchain_guess.yaml",
                  target=CALIBRATION / "aprilgrid.yaml")
    run_tool("calibrate", *[f"--{k}={v}" for k, v in inputs.items()],
             "--imu-yaml", sim / "imu.yaml", "--out", tmp_path / "out")
    expected = load_yaml(tmp_path / "out" / "result.yaml")
    result = splinecal.calibrate(**inputs, imu_yaml=sim / "imu.yaml")
    spline = result.pop("se3_spline")
    for key in WALL_TIMES:
        result[key] = expected[key]
    assert_same(result, expected, tol=TOLERANCE)
    assert spline.num_control_poses > 4
