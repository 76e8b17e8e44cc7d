"""detect on a rendered checkerboard against `splinecal detect` on the same image as a PNG."""
import pathlib
import struct
import zlib

import numpy as np
import pytest

import splinecal
from conftest import DATA, read_csv_columns, run_tool

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
    with pytest.raises(splinecal.Error, match="1000.png"):
        splinecal.detect([bad], target)
    with pytest.raises(ValueError, match=r"image\[1\]"):
        splinecal.detect([bad, 3], target)
