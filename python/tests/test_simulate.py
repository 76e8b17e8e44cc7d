"""simulate's out= against `splinecal simulate`: the same seed gives byte-identical files."""
import splinecal
from conftest import DATA, assert_same_files, run_tool

FILES = ("mav0/imu0/data.csv", "mav0/state_groundtruth_estimate0/data.csv", "spline.csv",
         "imu.yaml", "result.yaml", "observations.csv", "camchain.yaml")


def test_simulate_out_writes_the_command_s_files(tmp_path):
    camchain, target = DATA / "calibration/camchain_truth.yaml", DATA / "calibration/aprilgrid.yaml"
    run_tool("simulate", "--trajectory", "calibration", "--duration", 3, "--seed", 4,
             "--camchain", camchain, "--target", target, "--out", tmp_path / "cli")
    splinecal.simulate(trajectory="calibration", duration=3, seed=4, camchain=camchain,
                       target=target, out=tmp_path / "py")
    assert_same_files(tmp_path / "py", tmp_path / "cli", FILES)
