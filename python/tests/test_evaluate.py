"""evaluate against `splinecal evaluate` on the bundled spline."""
import numpy as np

import splinecal
from conftest import (DATA, assert_same, assert_same_files, load_yaml, read_csv_columns,
                      run_tool)

SPLINE = DATA / "vio_course_spline.csv"
FLAGS = dict(samples=7, every=0.5, gravity=9.8, gyro_bias=[0.01, 0.0, -0.02],
             accel_bias=[0.1, 0.2, 0.0])


def test_evaluate_writes_the_command_s_files(tmp_path):
    run_tool("evaluate", "--spline", SPLINE, "--samples", 7, "--every", 0.5, "--gravity", 9.8,
             "--gyro-bias", "0.01,0,-0.02", "--accel-bias", "0.1,0.2,0", "--out", tmp_path / "cli")
    result = splinecal.evaluate(str(SPLINE), **FLAGS, out=tmp_path / "py")
    # The same library call formats both: identical files, result.yaml included.
    assert_same_files(tmp_path / "py", tmp_path / "cli",
                      ("samples.csv", "evaluation.csv", "result.yaml"))
    samples = result.pop("samples")
    assert_same(result, load_yaml(tmp_path / "cli" / "result.yaml"), tol=0)
    # The arrays are the rows of samples.csv (%.17g there: exact).
    t_ns, columns = read_csv_columns(tmp_path / "cli" / "samples.csv")
    np.testing.assert_array_equal(samples["t_ns"], t_ns)
    np.testing.assert_array_equal(samples["T_w_s"][:, :3, 3], columns[:, 0:3])
    np.testing.assert_array_equal(samples["gyro"], columns[:, 16:19])
    np.testing.assert_array_equal(samples["accel"], columns[:, 19:22])


def test_evaluate_of_a_spline_object_equals_evaluate_of_its_file():
    from_file = splinecal.evaluate(SPLINE, **FLAGS)
    from_object = splinecal.evaluate(splinecal.SE3Spline.read_csv(SPLINE), **FLAGS)
    assert from_object.pop("spline") == ""  # no file to name
    from_file.pop("spline")
    for key in ("t_ns", "T_w_s", "w_s", "v_w", "a_w", "gyro", "accel"):
        np.testing.assert_array_equal(from_object["samples"].pop(key),
                                      from_file["samples"].pop(key))
    assert from_object.keys() == from_file.keys()
    assert_same({k: v for k, v in from_object.items() if k != "samples"},
                {k: v for k, v in from_file.items() if k != "samples"}, tol=0)
