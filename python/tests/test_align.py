"""align against `splinecal align` on a simulated figure eight, its ground truth at 10 Hz shrunk
to half size standing in for up-to-scale camera poses."""
import numpy as np

import splinecal
from conftest import (assert_same, assert_same_files, load_yaml, quaternion_to_matrix,
                      read_csv_columns, run_tool)

SHRINK = 0.5  # camera positions = SHRINK * metric positions: the true scale is 1 / SHRINK


def simulated(tmp_path):
    """10 s of a figure eight with EuRoC's IMU noise and no biases (align assumes a known
    accelerometer bias): the IMU file and the ground truth's file."""
    splinecal.simulate(trajectory="figure8", duration=10, seed=7, out=tmp_path / "sim")
    return (tmp_path / "sim/mav0/imu0/data.csv",
            tmp_path / "sim/mav0/state_groundtruth_estimate0/data.csv")


def shrunk_poses(tmp_path, truth):
    """Every 20th ground-truth row (10 Hz) with positions times SHRINK, as a file and as a dict:
    T_c0_c with T_cam_imu the identity (no camchain)."""
    t_ns, columns = read_csv_columns(truth)
    t_ns, columns = t_ns[::20], columns[::20]
    columns[:, 0:3] *= SHRINK
    path = tmp_path / "poses.csv"
    with open(path, "w") as f:
        f.write("#t_ns,px,py,pz,qw,qx,qy,qz,vx,vy,vz,bwx,bwy,bwz,bax,bay,baz\n")
        for t, row in zip(t_ns, columns):
            f.write(f"{t}," + ",".join(f"{v:.17g}" for v in row) + "\n")
    T = np.tile(np.eye(4), (len(t_ns), 1, 1))
    q = columns[:, 3:7] / np.linalg.norm(columns[:, 3:7], axis=1)[:, None]
    T[:, :3, :3] = quaternion_to_matrix(q)
    T[:, :3, 3] = columns[:, 0:3]
    return path, {"t_ns": t_ns, "T_w_s": T}


def test_align_equals_the_command_line(tmp_path):
    imu, truth = simulated(tmp_path)
    path, poses = shrunk_poses(tmp_path, truth)
    run_tool("align", "--imu", imu, "--camera-poses", path, "--out", tmp_path / "cli")
    result = splinecal.align(imu, path, out=tmp_path / "py")
    assert_same_files(tmp_path / "py", tmp_path / "cli", ("result.yaml", "aligned_poses.csv"))
    aligned = result.pop("aligned_poses")
    assert_same(result, load_yaml(tmp_path / "cli" / "result.yaml"), tol=0)
    t_ns, rows = read_csv_columns(tmp_path / "cli" / "aligned_poses.csv")
    np.testing.assert_array_equal(aligned["t_ns"], t_ns)
    np.testing.assert_array_equal(aligned["T_w_s"][:, :3, 3], rows[:, 0:3])
    # The metric scale of the shrunk poses, up to the IMU noise (docs/align.md's example gets
    # its scale to 3e-3 from 10 s of the same noise).
    assert abs(result["scale"] * SHRINK - 1.0) < 0.02, result["scale"]

    # The same poses as arrays give the same alignment.
    from_arrays = splinecal.align(imu, poses)
    from_arrays.pop("aligned_poses")
    # quaternion -> matrix -> quaternion rounds at 1e-16; the solve amplifies it by its condition
    # number (tens), far below 1e-9.
    assert_same(from_arrays, result, tol=1e-9)
