"""calibrate against `splinecal calibrate` on a short simulated AprilGrid recording."""
import numpy as np
import pytest

import splinecal
from conftest import DATA, assert_same, load_yaml, run_tool, tool_error

CALIBRATION = DATA / "calibration"
# The same C++ solve on the same files, one thread: only wall times differ, and the command line
# (the tool's flags as typed; the module's call).
TOLERANCE = 1e-9
WALL_TIMES = ("initialisation_time_s", "solve_time_s", "covariance_time_s", "command_line")


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


def test_calibrate_with_the_command_s_camera_choices_and_initial_poses(tmp_path):
    """--cameras, --hold-camera-chain and --initial-poses (with a target: the initial guess
    comes from the poses instead of PnP) as keywords, and out= writing the command's files."""
    sim = tmp_path / "sim"
    simulated = splinecal.simulate(trajectory="calibration", duration=5, seed=2,
                                   camchain=CALIBRATION / "camchain_truth.yaml",
                                   target=CALIBRATION / "aprilgrid.yaml", out=sim)
    inputs = dict(imu=sim / "mav0/imu0/data.csv", observations=sim / "observations.csv",
                  camchain=CALIBRATION / "camchain_guess.yaml",
                  target=CALIBRATION / "aprilgrid.yaml", cameras="0",
                  initial_poses=sim / "mav0/state_groundtruth_estimate0/data.csv",
                  imu_yaml=sim / "imu.yaml")
    run_tool("calibrate", *[f"--{k.replace('_', '-')}={v}" for k, v in inputs.items()],
             "--hold-camera-chain", "--out", tmp_path / "cli")
    expected = load_yaml(tmp_path / "cli" / "result.yaml")
    result = splinecal.calibrate(**inputs, hold_camera_chain=True, out=tmp_path / "py")
    result.pop("se3_spline")
    for key in WALL_TIMES:
        result[key] = expected[key]
    assert_same(result, expected, tol=TOLERANCE)
    for name in ("camchain-imucam.yaml", "spline.csv", "reprojection_errors.csv"):
        assert (tmp_path / "py" / name).read_text() == (tmp_path / "cli" / name).read_text(), name
    assert (tmp_path / "py" / "report.html").exists()

    # The initial poses as arrays (simulate's ground truth) and cameras as a list.
    truth = simulated["ground_truth"]
    from_arrays = splinecal.calibrate(**{**inputs, "cameras": [0],
                                         "initial_poses": {"t_ns": truth["t_ns"],
                                                           "T_w_s": truth["T_w_s"]}},
                                      hold_camera_chain=True)
    from_arrays.pop("se3_spline")
    for key in WALL_TIMES:
        from_arrays[key] = expected[key]
    # The arrays' rotations pass quaternion -> matrix -> quaternion (1e-16 apart from the file's):
    # a slightly different initial guess, the same minimum to the solver's tolerance (relative
    # cost change 1e-10). Ceres' termination line quotes the last cost change.
    from_arrays["termination"] = expected["termination"]
    assert_same(from_arrays, expected, tol=1e-6)


def test_calibrate_refuses_as_the_command_does(tmp_path):
    camchain = CALIBRATION / "camchain_guess.yaml"
    observations = tmp_path / "obs.csv"
    observations.write_text("#t_ns,cam_id,point_id,u,v\n1000000000,0,1,10.0,20.0\n")
    message = tool_error("calibrate", "--imu", "imu.csv", "--observations", observations,
                         "--camchain", camchain, "--target", CALIBRATION / "aprilgrid.yaml",
                         "--cameras", "2", "--out", tmp_path / "o")
    with pytest.raises(splinecal.Error) as error:
        splinecal.calibrate("imu.csv", observations, camchain, CALIBRATION / "aprilgrid.yaml",
                            cameras=[2])
    assert message == "splinecal calibrate: " + str(error.value)
    with pytest.raises(ValueError, match="initial_poses"):
        splinecal.calibrate("imu.csv", observations, camchain)


def test_calibrate_several_imus_equals_the_command_line(tmp_path):
    """Several IMUs (docs/calibrate.md, "Several IMUs"): imu as a list equals --imu a,b, and
    result.yaml's imu1 section comes back; lists of other lengths are refused naming the keyword."""
    sim = tmp_path / "sim"
    run_tool("simulate", "--trajectory", "calibration", "--duration", 5,
             "--camchain", CALIBRATION / "camchain_truth.yaml",
             "--target", CALIBRATION / "aprilgrid.yaml", "--seed", 2,
             "--imu-intrinsics", DATA / "imu_models" / "rig_three_imus.yaml", "--out", sim)
    imus = [sim / "mav0/imu0/data.csv", sim / "mav0/imu1/data.csv"]
    inputs = dict(observations=sim / "observations.csv",
                  camchain=CALIBRATION / "camchain_guess.yaml",
                  target=CALIBRATION / "aprilgrid.yaml")
    run_tool("calibrate", f"--imu={imus[0]},{imus[1]}",
             *[f"--{k}={v}" for k, v in inputs.items()],
             "--imu-yaml", sim / "imu.yaml", "--out", tmp_path / "out")
    expected = load_yaml(tmp_path / "out" / "result.yaml")
    result = splinecal.calibrate(imu=imus, **inputs, imu_yaml=[sim / "imu.yaml"] * 2)
    result.pop("se3_spline")
    for key in WALL_TIMES:
        result[key] = expected[key]
    assert_same(result, expected, tol=TOLERANCE)
    assert result["imu1"]["model"] == "calibrated"
    with pytest.raises(ValueError, match="imu_yaml: 3 entries for 2 IMU"):
        splinecal.calibrate(imu=imus, **inputs, imu_yaml=[sim / "imu.yaml"] * 3)
    # imu_model: one per IMU, each further IMU with its own model (refused before any solve).
    with pytest.raises(ValueError, match="imu_model: 3 entries for 2 IMU"):
        splinecal.calibrate(imu=imus, **inputs, imu_model="calibrated,scale-misalignment,calibrated")
    with pytest.raises(ValueError, match="imu_model: 'scale-misalign' is not one of"):
        splinecal.calibrate(imu=imus, **inputs, imu_model="calibrated,scale-misalign")
