"""The bag keywords (bag=, imu_topic=, bag_time=, image_topics=) of detect, integrate, fit, allan
and calibrate against the command line's --bag, on data/bags/ros1_calibration.bag
(scripts/fixtures/make_calibration_bag.py): the same results as the command, and the same
results as the samples and frames the bag was written from."""
import numpy as np
import pytest

import splinecal
from conftest import DATA, EUROC, assert_same, load_yaml, run_tool, tool_error

BAG = DATA / "bags" / "ros1_calibration.bag"
TARGET = DATA / "euroc_april_frames" / "aprilgrid.yaml"
CAMERAS = [DATA / "euroc_april_frames" / "cam0", DATA / "euroc_april_frames" / "cam1"]


def euroc_head(tmp_path):
    """The rows the bag's /imu0 holds: the first 800 of the bundled EuRoC IMU, with its header."""
    lines = (EUROC / "imu0.csv").read_text().splitlines(keepends=True)
    path = tmp_path / "imu0_head.csv"
    path.write_text("".join(lines[:801]))
    return path


def test_detect_on_the_bag_equals_the_command_and_the_bundled_frames(tmp_path):
    topics = ["/cam0/image_raw", "/cam1/image_raw"]
    run_tool("detect", "--bag", BAG, "--image-topics", ",".join(topics), "--target", TARGET,
             "--out", tmp_path / "cli")
    result = splinecal.detect(bag=BAG, image_topics=topics, target=TARGET, out=tmp_path / "py")
    assert (tmp_path / "py" / "observations.csv").read_bytes() == \
        (tmp_path / "cli" / "observations.csv").read_bytes()
    folders = splinecal.detect(images=CAMERAS, target=TARGET)
    for key in ("t_ns", "cam_id", "point_id", "uv"):
        np.testing.assert_array_equal(result["observations"][key], folders["observations"][key])
    assert len(result["observations"]["t_ns"]) == 288  # 144 corners in each camera


def test_integrate_from_the_bag_equals_its_rows_as_a_file(tmp_path):
    from_bag = splinecal.integrate(bag=BAG, imu_topic="/imu0",
                                   groundtruth=EUROC / "groundtruth.csv")
    from_file = splinecal.integrate(euroc_head(tmp_path), EUROC / "groundtruth.csv")
    assert_same(from_bag, from_file, tol=0)


def test_allan_from_the_bag_equals_the_command(tmp_path):
    run_tool("allan", "--bag", BAG, "--imu-topic", "/imu0", "--allow-motion", "--out",
             tmp_path / "cli")
    result = splinecal.allan(bag=BAG, imu_topic="/imu0", allow_motion=True)
    cli = load_yaml(tmp_path / "cli" / "result.yaml")
    assert result["source"] == cli["source"] == f"{BAG}:/imu0"
    assert_same(result, cli, tol=0)


def test_fit_from_the_bag_equals_its_rows_as_a_file(tmp_path):
    from_bag = splinecal.fit(bag=[BAG], imu_topic="/imu0", poses=EUROC / "groundtruth.csv")
    from_file = splinecal.fit(euroc_head(tmp_path), EUROC / "groundtruth.csv")
    for key in ("gyro_bias", "accel_bias", "gravity_w"):
        assert key in from_bag
        np.testing.assert_array_equal(np.asarray(from_bag[key]), np.asarray(from_file[key]))


def test_calibrate_from_the_bag_equals_the_command(tmp_path):
    inputs = {"observations": DATA / "bags" / "ros1_calibration_observations.csv",
              "camchain": DATA / "calibration" / "camchain_guess.yaml",
              "target": DATA / "calibration" / "aprilgrid.yaml"}
    run_tool("calibrate", "--bag", BAG, "--imu-topic", "/sim/imu0",
             *[x for key, value in inputs.items() for x in (f"--{key}", value)],
             "--out", tmp_path / "cli")
    result = splinecal.calibrate(bag=BAG, imu_topic="/sim/imu0", **inputs)
    cli = load_yaml(tmp_path / "cli" / "result.yaml")
    # The estimates exactly; the stds move by a few 1e-16 relative with nothing but the input's
    # name (tests/cli/bag_input_test.cc measured it), hence their tolerance.
    np.testing.assert_array_equal(np.asarray(result["T_cam_imu"]), np.asarray(cli["T_cam_imu"]))
    assert result["timeshift_cam_imu"] == cli["timeshift_cam_imu"]
    assert result["rotation_std_deg"] == pytest.approx(cli["rotation_std_deg"], rel=1e-12)


def test_bag_errors_are_those_of_the_command(tmp_path):
    with pytest.raises(ValueError, match="exactly one"):
        splinecal.integrate(EUROC / "imu0.csv", EUROC / "groundtruth.csv", bag=BAG)
    with pytest.raises(TypeError, match="missing required argument 'groundtruth'"):
        splinecal.integrate(bag=BAG)
    message = tool_error("fit", "--bag", BAG, "--imu-topic", "/imu", "--poses",
                         EUROC / "groundtruth.csv", "--out", tmp_path / "out")
    with pytest.raises(splinecal.Error) as error:
        splinecal.fit(bag=BAG, imu_topic="/imu", poses=EUROC / "groundtruth.csv")
    assert message == "splinecal fit: " + str(error.value)
    assert "(its sensor_msgs/Imu topics: /imu0, /sim/imu0)" in message
    with pytest.raises(TypeError, match="image_topics"):
        splinecal.detect(images=CAMERAS, target=TARGET, image_topics=["/cam0/image_raw"])


def test_bag_info_lists_what_the_command_prints():
    info = splinecal.bag_info(BAG)
    printed = run_tool("bag", "info", BAG)
    assert info["format"] == "ROS 1 bag 2.0" and "format:    ROS 1 bag 2.0" in printed
    assert info["messages"] == 1403 and "messages:  1403" in printed
    imu = info["topics"]["/imu0"]
    assert (imu["type"], imu["messages"], imu["read_by_splinecal"]) == \
        ("sensor_msgs/Imu", 800, True)
    # EuRoC's 200 Hz stamps are not exactly 5 ms apart: 199.999997 Hz over these 800 rows.
    assert imu["rate_hz"] == pytest.approx(200.0, rel=1e-6)
    assert f"{imu['rate_hz']:8.3f} Hz  max gap {imu['max_gap_s'] * 1e3:.1f} ms" in printed
    assert info["warnings"] == []


def test_bag_extract_writes_what_the_command_writes(tmp_path):
    run_tool("bag", "extract", BAG, "--topics", "/imu0,/cam0/image_raw", "--out", tmp_path / "cli")
    result = splinecal.bag_extract(BAG, tmp_path / "py", topics=["/imu0", "/cam0/image_raw"])
    assert result["folders"]["imu0"]["messages"] == 800
    assert result["folders"]["cam0"]["topic"] == "/cam0/image_raw"
    for name in ("imu0/data.csv", "cam0/data.csv", "cam0/data/1403709395937837056.png",
                 "result.yaml"):
        assert (tmp_path / "py" / name).read_bytes() == (tmp_path / "cli" / name).read_bytes(), name
    assert result == load_yaml(tmp_path / "cli" / "result.yaml")
    with pytest.raises(splinecal.Error, match="--topics: /cam2 is not in the recording"):
        splinecal.bag_extract(BAG, tmp_path / "bad", topics="/cam2")
    assert not (tmp_path / "bad").exists()
