"""detect on a rendered checkerboard against `splinecal detect` on the same image as a PNG."""
import pathlib
import struct
import subprocess
import zlib

import numpy as np
import pytest

import splinecal
from conftest import (DATA, TOOL, assert_same, assert_same_files, load_yaml, read_csv_columns,
                      run_tool, tool_error)

SQUARE_PX = 24


def checkerboard(cols=9, rows=6):
    """Inner corners cols x rows: (cols + 1) x (rows + 1) squares on a white margin, blurred."""
    squares = (np.indices((rows + 1, cols + 1)).sum(axis=0) % 2) * 255
    board = np.kron(squares, np.ones((SQUARE_PX, SQUARE_PX)))
    image = np.pad(board, 2 * SQUARE_PX, constant_values=255.0)
    for axis in (0, 1):  # a 3-tap blur: real corners are not one-pixel steps
        image = (np.roll(image, 1, axis) + 2 * image + np.roll(image, -1, axis)) / 4
    return image.round().astype(np.uint8)


def write_png(path, image):
    """8-bit grayscale PNG, no filter (enough for the test; the detector reads any PNG)."""
    def chunk(kind, data):
        return (struct.pack(">I", len(data)) + kind + data +
                struct.pack(">I", zlib.crc32(kind + data) & 0xFFFFFFFF))
    h, w = image.shape
    raw = b"".join(b"\x00" + image[r].tobytes() for r in range(h))
    path.write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, 8, 0, 0, 0, 0))
                     + chunk(b"IDAT", zlib.compress(raw)) + chunk(b"IEND", b""))


@pytest.fixture
def target(tmp_path):
    path = tmp_path / "checkerboard.yaml"
    path.write_text("target_type: checkerboard\ntargetCols: 9\ntargetRows: 6\n"
                    "rowSpacingMeters: 0.03\ncolSpacingMeters: 0.03\n")
    return path


def test_detect_equals_the_command_line(tmp_path, target):
    image = checkerboard()
    (tmp_path / "images").mkdir()
    write_png(tmp_path / "images" / "1000000000.png", image)
    run_tool("detect", "--images", tmp_path / "images", "--target", target, "--out", tmp_path / "out")
    _, columns = read_csv_columns(tmp_path / "out" / "observations.csv")  # cam_id, point_id, u, v
    result = splinecal.detect(image, target)
    assert len(result["point_id"]) == 54
    np.testing.assert_array_equal(result["point_id"], columns[:, 1].astype(np.int64))
    np.testing.assert_allclose(result["uv"], columns[:, 2:4], rtol=0, atol=1e-12)
    # The corners lie on the square boundaries, (k + 2) * SQUARE_PX - 0.5 in pixel centres.
    grid = (np.arange(1, 10) + 2) * SQUARE_PX - 0.5
    assert np.all(np.min(np.abs(result["uv"][:, 0:1] - grid[None, :]), axis=1) < 0.1)


def test_detect_takes_any_memory_layout(target):
    image = checkerboard()
    fortran = splinecal.detect(np.asfortranarray(image), target)
    np.testing.assert_array_equal(fortran["uv"], splinecal.detect(image, target)["uv"])


def observations_by_frame(csv_path):
    """observations.csv of `splinecal detect` as {t_ns: (point_id (k,), uv (k, 2))}."""
    t_ns, columns = read_csv_columns(csv_path)  # columns: cam_id, point_id, u, v
    frames = {}
    for t in np.unique(t_ns):
        rows = columns[t_ns == t]
        frames[int(t)] = (rows[:, 1].astype(np.int64), rows[:, 2:4])
    return frames


@pytest.mark.parametrize("folder, target", [
    ("euroc_april_frames/cam0", "euroc_april_frames/aprilgrid.yaml"),     # EuRoC layout, PNG
    ("opencv_chessboard/cam0", "opencv_chessboard/checkerboard.yaml"),  # plain folder, JPEG
])
def test_files_give_the_corners_of_the_command_line(tmp_path, folder, target):
    folder, target = DATA / folder, DATA / target
    run_tool("detect", "--images", folder, "--target", target, "--out", tmp_path / "out")
    expected = observations_by_frame(tmp_path / "out" / "observations.csv")
    frames = splinecal.detect(folder, target)
    assert [f["t_ns"] for f in frames] == sorted(expected)
    for frame in frames:
        point_id, uv = expected[frame["t_ns"]]
        # The same decoder and detector: the same corners to the last bit written (17 digits).
        np.testing.assert_array_equal(frame["point_id"], point_id)
        np.testing.assert_allclose(frame["uv"], uv, rtol=0, atol=1e-12)
    # A list of the same files, and one file alone, give the same dicts.
    paths = [frame["path"] for frame in frames]
    listed = splinecal.detect(paths, target)
    assert [f["path"] for f in listed] == paths
    for a, b in zip(listed, frames):
        np.testing.assert_array_equal(a["uv"], b["uv"])
    single = splinecal.detect(pathlib.Path(paths[0]), target)
    np.testing.assert_array_equal(single["uv"], frames[0]["uv"])


def test_effort_is_checked_and_fast_still_finds_the_euroc_grid():
    target = DATA / "euroc_april_frames" / "aprilgrid.yaml"
    frame = DATA / "euroc_april_frames" / "cam0"
    assert len(splinecal.detect(frame, target, effort="fast")[0]["point_id"]) == 144
    with pytest.raises(ValueError, match="effort"):
        splinecal.detect(frame, target, effort="slow")


def test_a_file_that_is_no_image_names_itself(tmp_path, target):
    bad = tmp_path / "1000.png"
    bad.write_bytes(b"not an image")
    # Warned as the command line warns, then none readable: an error naming it.
    with pytest.raises(splinecal.Error, match="1000.png"), pytest.warns(UserWarning, match="1000.png"):
        splinecal.detect([bad], target)
    with pytest.raises(ValueError, match=r"image\[1\]"):
        splinecal.detect([bad, 3], target)


APRIL = DATA / "euroc_april_frames"


def tool_warnings(*args):
    """The "detect: warning: ..." lines of a `splinecal detect` run (exit 0), without the prefix."""
    done = subprocess.run([TOOL, "detect", *map(str, args)], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    prefix = "detect: warning: "
    return [line[len(prefix):] for line in done.stderr.splitlines() if line.startswith(prefix)]


def test_images_keyword_is_the_command_with_the_same_files(tmp_path):
    folders = [APRIL / "cam0", APRIL / "cam1"]
    target = APRIL / "aprilgrid.yaml"
    run_tool("detect", "--images", ",".join(map(str, folders)), "--target", target,
             "--draw", "--out", tmp_path / "cli")
    result = splinecal.detect(images=folders, target=target, out=tmp_path / "py", draw=True)
    assert_same_files(tmp_path / "py", tmp_path / "cli",
                      ["observations.csv", "overlays/cam0/1403709395937837056.png",
                       "overlays/cam1/1403709395937837056.png"])
    # result.yaml: the same but for the times of this run.
    expected = load_yaml(tmp_path / "cli" / "result.yaml")
    written = load_yaml(tmp_path / "py" / "result.yaml")
    for run in (expected, written, result):
        run.pop("wall_time_s")
        for camera in run["cameras"].values():
            camera.pop("detection_time_s")
    assert_same(written, expected, 0)
    # The dict is result.yaml's, with the observations themselves where the file names
    # observations.csv (as splinecal.simulate returns them).
    assert expected.pop("observations") == "observations.csv"
    observations = result.pop("observations")
    assert_same(result, expected, 0)
    assert result["cameras"]["cam1"]["corners"] == 144
    # The observations returned are the file's rows.
    t_ns, columns = read_csv_columns(tmp_path / "cli" / "observations.csv")
    np.testing.assert_array_equal(observations["t_ns"], t_ns)
    np.testing.assert_array_equal(observations["point_id"], columns[:, 1].astype(np.int64))
    np.testing.assert_allclose(observations["uv"], columns[:, 2:4], rtol=0, atol=1e-12)
    # A comma-separated str, as --images, and one thread: the same corners.
    again = splinecal.detect(images=",".join(map(str, folders)), target=target, threads=1)
    np.testing.assert_array_equal(again["observations"]["uv"], observations["uv"])


def folder_with_a_bad_frame(tmp_path):
    """A plain folder: the EuRoC frame as 1000.png and a file that is no image as 2000.png."""
    folder = tmp_path / "frames"
    folder.mkdir()
    (folder / "1000.png").write_bytes(
        (APRIL / "cam0" / "data" / "1403709395937837056.png").read_bytes())
    (folder / "2000.png").write_bytes(b"not an image")
    return folder


def test_python_warns_where_the_command_line_warns(tmp_path):
    folder = folder_with_a_bad_frame(tmp_path)
    target = APRIL / "aprilgrid.yaml"
    expected = tool_warnings("--images", folder, "--target", target, "--out", tmp_path / "cli")
    assert len(expected) == 1 and "2000.png" in expected[0], expected
    # The command (images=) and a folder (image): the command line's line, word for word.
    for call in (lambda: splinecal.detect(images=[folder], target=target),
                 lambda: splinecal.detect(folder, target)):
        with pytest.warns(UserWarning) as caught:
            result = call()
        assert [str(w.message) for w in caught] == expected
    frames = splinecal.detect(folder, target)
    assert [f["t_ns"] for f in frames] == [1000] and len(frames[0]["point_id"]) == 144
    # A list of files: the same warning for the bad one, which is left out.
    with pytest.warns(UserWarning, match="2000.png.*frame skipped"):
        listed = splinecal.detect([folder / "1000.png", folder / "2000.png"], target)
    assert [pathlib.Path(f["path"]).name for f in listed] == ["1000.png"]


def test_errors_of_the_command_are_errors_in_python(tmp_path, target):
    april = APRIL / "aprilgrid.yaml"
    # No frame shows the target: the command's exit 2 and its line.
    message = tool_error("detect", "--images", APRIL / "cam0", "--target", target,
                         "--out", tmp_path / "cli")
    with pytest.raises(splinecal.Error) as raised:
        splinecal.detect(images=[APRIL / "cam0"], target=target, out=tmp_path / "py")
    assert str(raised.value) in message
    assert not (tmp_path / "py" / "result.yaml").exists()
    with pytest.raises(ValueError, match="draw.*out"):
        splinecal.detect(images=[APRIL / "cam0"], target=april, draw=True)
    with pytest.raises(TypeError, match="out"):
        splinecal.detect(APRIL / "cam0", april, out=tmp_path / "py")
    with pytest.raises(TypeError, match="not both"):
        splinecal.detect(APRIL / "cam0", april, images=[APRIL / "cam0"])
    with pytest.raises(ValueError, match="threads"):
        splinecal.detect(images=[APRIL / "cam0"], target=april, threads=0)


def test_a_target_file_that_contradicts_the_board_is_the_commands_error(tmp_path):
    grid = tmp_path / "grid7.yaml"
    grid.write_text("target_type: aprilgrid\ntagCols: 7\ntagRows: 7\ntagSize: 0.088\n"
                    "tagSpacing: 0.3\n")
    message = tool_error("detect", "--images", APRIL / "cam0", "--target", grid,
                         "--out", tmp_path / "cli")
    assert "lie on an aprilgrid of 6 tag columns, not the 7 of this file" in message
    with pytest.raises(splinecal.Error) as raised:
        splinecal.detect(images=[APRIL / "cam0"], target=grid, out=tmp_path / "py")
    assert str(raised.value) in message
    assert not (tmp_path / "py" / "observations.csv").exists()
