"""splinecal.correct: the command's correction of raw readings simulated through an IMU model."""
import numpy as np
import pytest

import splinecal

INTRINSICS = """imu0:
  model: scale-misalignment
  accelerometers:
    M: [[1.01, 0, 0], [0.008, 0.99, 0], [-0.006, 0.004, 1.005]]
  gyroscopes:
    M: [[0.99, 0, 0], [-0.005, 1.012, 0], [0.007, -0.003, 1.008]]
    A: [[0.001, 0, 0], [0, -0.0008, 0], [0, 0, 0.0009]]
    C_gyro_i: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]
"""


def test_correct_inverts_the_simulated_model(tmp_path):
    intrinsics = tmp_path / "imus.yaml"
    intrinsics.write_text(INTRINSICS)
    raw = splinecal.simulate(duration=2, noise_free=True, imu_intrinsics=str(intrinsics))
    plain = splinecal.simulate(duration=2, noise_free=True)
    result = splinecal.correct(raw["imu"], str(intrinsics), out=str(tmp_path / "out"))
    assert result["model"] == "scale-misalignment"
    assert result["num_samples"] == len(plain["imu"]["t_ns"])
    # Noise-free readings without biases: the correction is the plain simulation's readings
    # (the calibrated model at the body origin) to rounding of O(10) values.
    np.testing.assert_allclose(result["imu"]["gyro"], plain["imu"]["gyro"], atol=1e-12)
    np.testing.assert_allclose(result["imu"]["accel"], plain["imu"]["accel"], atol=1e-12)
    # The raw readings are not: the model moved them by ~1e-2 m/s^2 and more.
    assert np.abs(raw["imu"]["accel"] - plain["imu"]["accel"]).max() > 1e-2
    assert (tmp_path / "out" / "mav0" / "imu0" / "data.csv").exists()


def test_correct_refuses_an_index_beyond_the_file(tmp_path):
    intrinsics = tmp_path / "imus.yaml"
    intrinsics.write_text(INTRINSICS)
    raw = splinecal.simulate(duration=1, noise_free=True)
    with pytest.raises(ValueError, match="imu_index"):
        splinecal.correct(raw["imu"], str(intrinsics), imu_index=1)
