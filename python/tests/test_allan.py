"""allan_deviation against a numpy overlapping Allan deviation; allan against `splinecal allan`."""
import numpy as np
import pytest

import splinecal
from conftest import assert_same, assert_same_files, load_yaml, run_tool, tool_error

RATE_HZ = 100.0


def overlapping_adev(y, rate_hz, tau):
    """IEEE Std 952 / NIST SP 1065 overlapping Allan deviation, from the phase theta."""
    y = np.asarray(y, dtype=np.longdouble)
    theta = np.concatenate([[0], np.cumsum(y - y.mean())]) / rate_hz
    n = len(y)
    adev = []
    for t in tau:
        m = int(round(t * rate_hz))
        d = theta[2 * m:] - 2 * theta[m:n + 1 - m] + theta[:n + 1 - 2 * m]
        adev.append(np.sqrt(np.sum(d * d) / (2 * t * t * (n - 2 * m + 1))))
    return np.array(adev, dtype=np.float64)


def noise(n, columns, seed):
    rng = np.random.default_rng(seed)
    white = rng.normal(0.0, 1e-2, (n, columns))
    walk = np.cumsum(rng.normal(0.0, 1e-4, (n, columns)), axis=0)
    return white + walk


def test_allan_deviation_equals_numpy():
    x = noise(20000, 3, seed=1)
    tau, adev = splinecal.allan_deviation(x, RATE_HZ, taus_per_decade=10)
    assert adev.shape == (len(tau), 3)
    assert np.all(np.diff(tau) > 0)
    for column in range(3):
        np.testing.assert_allclose(adev[:, column], overlapping_adev(x[:, column], RATE_HZ, tau),
                                   rtol=1e-10, atol=0)


def test_allan_deviation_of_one_column_is_one_dimensional():
    x = noise(5000, 1, seed=2)[:, 0]
    tau, adev = splinecal.allan_deviation(x, RATE_HZ)
    assert adev.shape == tau.shape
    np.testing.assert_allclose(adev, overlapping_adev(x, RATE_HZ, tau), rtol=1e-10, atol=0)


def test_allan_equals_the_command_line(tmp_path):
    rng = np.random.default_rng(3)
    n = 60000  # 10 minutes at 100 Hz
    imu = np.hstack([rng.normal(0.0, 1.7e-4 * 10, (n, 3)),
                     rng.normal(0.0, 2e-3 * 10, (n, 3)) + [0.0, 0.0, 9.81]])
    columns = tmp_path / "static.txt"
    np.savetxt(columns, imu, fmt="%.17g")
    run_tool("allan", "--columns", columns, "--rate", RATE_HZ, "--out", tmp_path / "out")
    expected = load_yaml(tmp_path / "out" / "result.yaml")
    result = splinecal.allan(imu, RATE_HZ)
    assert result["source"] == "numpy array"
    expected["source"] = "numpy array"  # the command names its file
    assert_same(result, expected, tol=1e-12)


def test_allan_work_budget():
    rng = np.random.default_rng(4)
    n = 20000
    imu = np.hstack([rng.normal(0.0, 1.7e-3, (n, 3)), rng.normal(0.0, 2e-2, (n, 3)) + [0, 0, 9.81]])
    strided = splinecal.allan(imu, RATE_HZ, taus_per_decade=1000)
    assert strided["max_passes"] == 100
    assert strided["strided_averaging_times"] > 0
    assert strided["passes_used"] <= 100
    exact = splinecal.allan(imu, RATE_HZ, taus_per_decade=1000, max_passes=0)
    assert exact["strided_averaging_times"] == 0
    assert exact["passes_used"] == exact["overlapping_passes"]


def static_in_g(n=20000, seed=5):
    """A static IMU whose accelerometer columns are in g (gravity reads 1): the command refuses
    it unless told the unit."""
    rng = np.random.default_rng(seed)
    return np.hstack([rng.normal(0.0, 1.7e-3, (n, 3)),
                      rng.normal(0.0, 2e-4, (n, 3)) + [0.0, 0.0, 1.0]])


def test_an_array_in_g_is_refused_as_the_command_refuses_the_file(tmp_path):
    imu = static_in_g()
    columns = tmp_path / "static_g.txt"
    np.savetxt(columns, imu, fmt="%.17g")
    message = tool_error("allan", "--columns", columns, "--rate", RATE_HZ, "--out", tmp_path / "o")
    with pytest.raises(splinecal.Error) as array_error:
        splinecal.allan(imu, RATE_HZ)
    # The same check: the command's line after its file name is the array's after its name.
    assert "looks like units of g" in str(array_error.value)
    assert message.split(f"{columns}:", 1)[1] == str(array_error.value).split("imu:", 1)[1]
    with pytest.raises(splinecal.Error, match="looks like units of g"):
        splinecal.allan(columns=columns, rate=RATE_HZ)
    # Told the unit, both read it.
    in_g = splinecal.allan(imu, RATE_HZ, accel_unit="g")
    assert in_g["accelerometer_noise_density"] > 0


def test_one_sensor_array_needs_the_sensor():
    gyro = static_in_g()[:, :3]
    with pytest.raises(splinecal.Error, match="say which sensor"):
        splinecal.allan(gyro, RATE_HZ)
    result = splinecal.allan(gyro, RATE_HZ, sensor="gyro")
    assert "gyroscope_noise_density" in result


def test_allan_out_writes_the_command_s_files(tmp_path):
    imu = static_in_g(seed=6)
    imu[:, 3:] *= 9.80665
    columns = tmp_path / "static.txt"
    np.savetxt(columns, imu, fmt="%.17g")
    run_tool("allan", "--columns", columns, "--rate", RATE_HZ, "--out", tmp_path / "cli")
    splinecal.allan(columns=columns, rate=RATE_HZ, out=tmp_path / "py")
    assert_same_files(tmp_path / "py", tmp_path / "cli",
                      ("allan.csv", "imu.yaml", "result.yaml", "allan.svg"))
