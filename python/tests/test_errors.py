"""Bad arguments: a ValueError naming the argument, never a crash; the library's errors with
the command line's one-line messages."""
import numpy as np
import pytest

import splinecal
from conftest import DATA, EUROC, tool_error

SPLINE = splinecal.SE3Spline.read_csv(DATA / "vio_course_spline.csv")
T0 = SPLINE.valid_range_ns()[0]


def imu_dict(n=400):
    t_ns = np.arange(n, dtype=np.int64) * 5_000_000 + 1_000_000_000
    return {"t_ns": t_ns, "gyro": np.zeros((n, 3)), "accel": np.tile([0.0, 0.0, 9.81], (n, 1))}


def poses_dict(n=100):
    return {"t_ns": np.arange(n, dtype=np.int64) * 20_000_000 + 1_000_000_000,
            "T_w_s": np.tile(np.eye(4), (n, 1, 1))}


@pytest.mark.parametrize("call, name", [
    (lambda: splinecal.SE3Spline(np.zeros((5, 4)), 0, 10), "control_poses"),
    (lambda: splinecal.SE3Spline(np.zeros((5, 4, 4)), 0, 10), r"control_poses\[0\]"),
    (lambda: splinecal.SE3Spline(np.tile(np.eye(4), (5, 1, 1)).astype(complex), 0, 10),
     "control_poses"),
    (lambda: SPLINE.evaluate(np.array([T0], dtype=np.float64)), "t_ns"),
    (lambda: SPLINE.evaluate(np.array([[T0]])), "t_ns"),
    (lambda: SPLINE.evaluate("now"), "t_ns"),
    (lambda: SPLINE.predict_imu([T0], gravity=float("nan")), "gravity"),
    (lambda: SPLINE.predict_imu([T0], gyro_bias=[0, 0]), "gyro_bias"),
    (lambda: SPLINE.predict_imu([T0], accel_bias=[0, np.inf, 0]), "accel_bias"),
    (lambda: splinecal.allan_deviation(np.ones((10, 2, 2)), 100.0), "x"),
    (lambda: splinecal.allan_deviation([1.0, np.nan] * 100, 100.0), "x"),
    (lambda: splinecal.allan_deviation(np.zeros(1000), -1.0), "rate_hz"),
    (lambda: splinecal.allan(np.zeros((1000, 5)), 100.0), "imu"),
    (lambda: splinecal.allan(np.zeros((1000, 6)), 100.0, combine="median"), "combine"),
    (lambda: splinecal.allan(np.zeros((1000, 6))), "rate"),
    (lambda: splinecal.detect(np.zeros((10, 10), dtype=np.float32),
                              DATA / "calibration/aprilgrid.yaml"), "image"),
    (lambda: splinecal.detect(np.zeros((10, 10, 3), dtype=np.uint8),
                              DATA / "calibration/aprilgrid.yaml"), "image"),
    (lambda: splinecal.simulate(duration=-1), "duration"),
    (lambda: splinecal.simulate(imu_rate=0), "imu_rate"),
    (lambda: splinecal.SE3Spline(SPLINE.control_poses, 0, 10, trajectory="so3"), "trajectory"),
    (lambda: splinecal.fit(imu_dict(), poses_dict(), bias_model="linear"), "bias_model"),
    (lambda: splinecal.fit(imu_dict(), poses_dict(), trajectory="coupled"), "trajectory"),
    (lambda: splinecal.fit(imu_dict(), poses_dict(), threads=0), "threads"),
    (lambda: splinecal.fit(42, poses_dict()), "imu"),
    (lambda: splinecal.fit({"t_ns": imu_dict()["t_ns"]}, poses_dict()), "gyro"),
])
def test_bad_argument_is_a_value_error_naming_it(call, name):
    with pytest.raises(ValueError, match=name):
        call()


def test_non_increasing_times_are_refused():
    imu = imu_dict()
    imu["t_ns"][7] = imu["t_ns"][6]
    with pytest.raises(ValueError, match=r"imu\['t_ns'\]: timestamps not increasing at row 7"):
        splinecal.fit(imu, poses_dict())
    poses = poses_dict()
    poses["t_ns"] = poses["t_ns"][::-1].copy()
    with pytest.raises(ValueError, match=r"poses\['t_ns'\]: timestamps not increasing at row 1"):
        splinecal.fit(imu_dict(), poses)


def test_float_times_and_nan_readings_are_refused():
    imu = imu_dict()
    imu["t_ns"] = imu["t_ns"].astype(np.float64)
    with pytest.raises(ValueError, match=r"imu\['t_ns'\]: expected int64 nanoseconds"):
        splinecal.fit(imu, poses_dict())
    imu = imu_dict()
    imu["accel"][3, 1] = np.nan
    with pytest.raises(ValueError, match=r"imu\['accel'\]: value nan"):
        splinecal.fit(imu, poses_dict())
    imu = imu_dict()
    imu["gyro"] = imu["gyro"][:-1]
    with pytest.raises(ValueError, match=r"imu\['gyro'\]: expected shape \(400, 3\)"):
        splinecal.fit(imu, poses_dict())
    poses = poses_dict()
    poses["T_w_s"][2, :3, :3] *= 2.0
    with pytest.raises(ValueError, match=r"poses\['T_w_s'\]\[2\]: not a pose"):
        splinecal.fit(imu_dict(), poses)


def test_library_errors_carry_the_command_line_message(tmp_path):
    missing = tmp_path / "missing.csv"
    cli = tool_error("fit", "--imu", missing, "--poses", EUROC / "groundtruth.csv",
                     "--out", tmp_path / "out")
    with pytest.raises(splinecal.Error) as error:
        splinecal.fit(missing, EUROC / "groundtruth.csv")
    assert cli == "splinecal fit: " + str(error.value)
    assert "\n" not in str(error.value)


def test_a_yaml_file_given_as_imu_says_so(tmp_path):
    with pytest.raises(splinecal.Error, match="imu_yaml"):
        splinecal.fit(EUROC / "sensor.yaml", EUROC / "groundtruth.csv")
