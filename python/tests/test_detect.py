"""detect on a rendered checkerboard against `splinecal detect` on the same image as a PNG."""
import struct
import zlib

import numpy as np
import pytest

import splinecal
from conftest import read_csv_columns, run_tool

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
