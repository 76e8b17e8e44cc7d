"""Shared helpers of the Python tests: the command-line tool they compare with, the bundled
data, and a comparison of a result dict with the tool's result.yaml.

ctest sets SPLINECAL_TOOL, SPLINECAL_SOURCE_DIR, SPLINECAL_SHARED_DATA_DIR and PYTHONPATH
(python/CMakeLists.txt). None of these tests reads ../shared/data; a test that does must call
shared_data(), which fails under CI=true when the data is missing and skips elsewhere.
"""
import math
import os
import pathlib
import subprocess

import numpy as np
import pytest
import yaml

SOURCE_DIR = pathlib.Path(os.environ.get(
    "SPLINECAL_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
TOOL = os.environ.get("SPLINECAL_TOOL", str(SOURCE_DIR / "build" / "splinecal"))
DATA = SOURCE_DIR / "data"
EUROC = DATA / "euroc_v1_01_easy_20s"


def shared_data(relative):
    """The path of ../shared/data/<relative>: a failure under CI=true when it is missing."""
    root = os.environ.get("SPLINECAL_SHARED_DATA_DIR", str(SOURCE_DIR.parent / "shared" / "data"))
    path = pathlib.Path(root) / relative
    if not path.exists():
        message = f"shared data missing: {path}"
        if os.environ.get("CI") == "true":
            pytest.fail(message)
        pytest.skip(message)
    return path


def run_tool(*args):
    """Runs `splinecal ARGS --quiet`; returns its stdout. Fails the test on a non-zero exit."""
    done = subprocess.run([TOOL, *map(str, args), "--quiet"], capture_output=True, text=True)
    assert done.returncode == 0, f"splinecal {' '.join(map(str, args))}: {done.stderr}"
    return done.stdout


def tool_error(*args):
    """The one-line error of a `splinecal` run that must fail with exit code 2."""
    done = subprocess.run([TOOL, *map(str, args), "--quiet"], capture_output=True, text=True)
    assert done.returncode == 2, done.stderr
    return done.stderr.strip()


def load_yaml(path):
    with open(path) as f:
        return yaml.safe_load(f)


def _number(value):
    # PyYAML reads YAML 1.1: '1e-05' (no dot) stays a string there, a float in the module.
    if isinstance(value, str):
        try:
            return float(value)
        except ValueError:
            return value
    return value


def assert_same(actual, expected, tol, path="result"):
    """Same keys and values; numbers equal within tol, absolute or relative."""
    actual, expected = _number(actual), _number(expected)
    if isinstance(expected, dict):
        assert isinstance(actual, dict), path
        assert sorted(actual) == sorted(expected), f"{path}: keys differ"
        for key in expected:
            assert_same(actual[key], expected[key], tol, f"{path}.{key}")
    elif isinstance(expected, list):
        assert isinstance(actual, list) and len(actual) == len(expected), path
        for i, (a, e) in enumerate(zip(actual, expected)):
            assert_same(a, e, tol, f"{path}[{i}]")
    elif isinstance(expected, bool) or expected is None or isinstance(expected, str):
        assert actual == expected, f"{path}: {actual!r} != {expected!r}"
    else:
        assert not isinstance(actual, (bool, str)), f"{path}: {actual!r} != {expected!r}"
        if math.isnan(expected):
            assert math.isnan(actual), path
        else:
            assert abs(actual - expected) <= tol * max(1.0, abs(expected)), \
                f"{path}: {actual!r} != {expected!r}"


def read_csv_columns(path):
    """A splinecal CSV (header '#...'): int64 first column, float64 the rest."""
    rows = [line.split(",") for line in pathlib.Path(path).read_text().splitlines()
            if line and not line.startswith("#")]
    t_ns = np.array([int(r[0]) for r in rows], dtype=np.int64)
    values = np.array([[float(x) for x in r[1:]] for r in rows])
    return t_ns, values


def quaternion_to_matrix(q_wxyz):
    w, x, y, z = np.moveaxis(q_wxyz, -1, 0)
    return np.stack([
        np.stack([1 - 2 * (y * y + z * z), 2 * (x * y - w * z), 2 * (x * z + w * y)], -1),
        np.stack([2 * (x * y + w * z), 1 - 2 * (x * x + z * z), 2 * (y * z - w * x)], -1),
        np.stack([2 * (x * z - w * y), 2 * (y * z + w * x), 1 - 2 * (x * x + y * y)], -1),
    ], -2)


def assert_same_files(actual_dir, expected_dir, names):
    """Each file of `names` has the same bytes in both folders (Python's out= and the command's
    --out: one library function formats both)."""
    for name in names:
        actual = (pathlib.Path(actual_dir) / name).read_bytes()
        assert actual == (pathlib.Path(expected_dir) / name).read_bytes(), name
