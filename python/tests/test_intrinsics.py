"""intrinsics against `splinecal intrinsics` on a short simulated AprilGrid recording."""
import pytest
import yaml

import splinecal
from conftest import DATA, assert_same, load_yaml, run_tool, tool_error

CALIBRATION = DATA / "calibration"


def simulated_observations(tmp_path):
    sim = splinecal.simulate(trajectory="calibration", duration=5, seed=2,
                             camchain=CALIBRATION / "camchain_truth.yaml",
                             target=CALIBRATION / "aprilgrid.yaml", out=tmp_path / "sim")
    return tmp_path / "sim" / "observations.csv", sim["observations"]


def without_wall_times(result, expected):
    """result with the command's wall time (the one value that differs between two runs)."""
    result["solver"]["solve_time_s"] = expected["solver"]["solve_time_s"]
    return result


def test_intrinsics_equals_the_command_line(tmp_path):
    observations, arrays = simulated_observations(tmp_path)
    flags = dict(target=CALIBRATION / "aprilgrid.yaml", models="pinhole-radtan",
                 camchain=CALIBRATION / "camchain_guess.yaml", threads=1)
    run_tool("intrinsics", "--observations", observations,
             *[f"--{k}={v}" for k, v in flags.items()], "--out", tmp_path / "cli")
    expected = load_yaml(tmp_path / "cli" / "result.yaml")
    result = splinecal.intrinsics(observations, **flags, out=tmp_path / "py")
    camchain = result.pop("camchain_yaml")
    # The covariance's last digits depend on summation order (the block sums): values to 1e-9.
    assert_same(yaml.safe_load(camchain),
                load_yaml(tmp_path / "cli" / "camchain.yaml"), tol=1e-9)
    assert (tmp_path / "py" / "camchain.yaml").read_text() == camchain
    assert (tmp_path / "py" / "report.html").exists()
    # The same C++ solve on the same files, one thread: only wall times may differ.
    assert_same(without_wall_times(result, expected), expected, tol=1e-9)
    assert yaml.safe_load(camchain)["cam0"]["camera_model"] == "pinhole"
    # The simulated target is its file: the test of its points is there and does not warn.
    check = result["target_points_check"]
    assert check["points"] > 0 and check["dof"] == 3 * check["points"] - 7
    assert check["chi_square"] < 4 * check["dof"]

    # The observations as arrays (simulate's) and the models as a list: the same calibration.
    from_arrays = splinecal.intrinsics(arrays, flags["target"], ["pinhole-radtan"],
                                       camchain=flags["camchain"], threads=1)
    from_arrays.pop("camchain_yaml")
    assert_same(without_wall_times(from_arrays, expected), expected, tol=1e-9)


def test_intrinsics_refuses_an_unknown_model_as_the_command_does(tmp_path):
    observations, _ = simulated_observations(tmp_path)
    message = tool_error("intrinsics", "--observations", observations, "--target",
                         CALIBRATION / "aprilgrid.yaml", "--models", "pinhole-radtann",
                         "--resolution", "752x480", "--out", tmp_path / "o")
    with pytest.raises(splinecal.Error) as error:
        splinecal.intrinsics(observations, CALIBRATION / "aprilgrid.yaml", "pinhole-radtann",
                             resolution="752x480")
    assert message == "splinecal intrinsics: " + str(error.value)


def test_intrinsics_compare_models_equals_the_command_line(tmp_path):
    observations, _ = simulated_observations(tmp_path)
    flags = dict(target=CALIBRATION / "aprilgrid.yaml", models="pinhole-radtan",
                 camchain=CALIBRATION / "camchain_guess.yaml", threads=1)
    run_tool("intrinsics", "--observations", observations,
             *[f"--{k}={v}" for k, v in flags.items()], "--compare-models",
             "--out", tmp_path / "cli")
    expected = load_yaml(tmp_path / "cli" / "result.yaml")
    result = splinecal.intrinsics(observations, **flags, compare_models=True)
    result.pop("camchain_yaml")
    models = [row["model"] for row in result["model_comparison"]]
    assert models == ["pinhole-radtan", "pinhole-equi", "ds-none"]
    assert_same(without_wall_times(result, expected), expected, tol=1e-9)


def command_and_module(tmp_path, observations, target_deformation):
    """intrinsics with target_deformation through the command (into tmp_path/cli) and the
    module; returns the flags and the module's result."""
    flags = dict(target=CALIBRATION / "aprilgrid.yaml", models="pinhole-radtan",
                 camchain=CALIBRATION / "camchain_guess.yaml", threads=1,
                 target_deformation=target_deformation)
    run_tool("intrinsics", "--observations", observations,
             *[f"--{k.replace('_', '-')}={v}" for k, v in flags.items()], "--out", tmp_path / "cli")
    return flags, splinecal.intrinsics(observations, **flags)


def test_intrinsics_target_deformation_equals_the_command_line(tmp_path):
    observations, _ = simulated_observations(tmp_path)
    flags, result = command_and_module(tmp_path, observations, "in-plane")
    expected = load_yaml(tmp_path / "cli" / "result.yaml")
    result.pop("camchain_yaml")
    block = result["target_deformation"]
    assert block["kind"] == "in-plane"
    assert [c["name"] for c in block["coefficients"]] == ["e1", "e2", "d"]
    assert_same(without_wall_times(result, expected), expected, tol=1e-9)
    # An unknown kind is refused with the names the command accepts.
    with pytest.raises(ValueError, match="target_deformation: expected none, quadratic, cubic, "
                                         "in-plane, in-plane-per-view, points, points-in-plane, "
                                         "got 'flat'"):
        splinecal.intrinsics(observations, flags["target"], flags["models"],
                             camchain=flags["camchain"], target_deformation="flat")


def test_intrinsics_free_target_returns_the_refined_target(tmp_path):
    observations, _ = simulated_observations(tmp_path)
    _, result = command_and_module(tmp_path, observations, "points")
    # The same refined target as the command writes, and a points target file.
    assert result["target_yaml"] == (tmp_path / "cli" / "target.yaml").read_text()
    assert result["target_yaml"].startswith("target_type: points\n")
    assert result["target_deformation"]["kind"] == "points"
