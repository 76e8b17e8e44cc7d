#!/usr/bin/env python3
"""Turns EuRoC ground truth (T_w_s) into up-to-scale camera poses T_c0_c in TUM format, as a
monocular SLAM system would report them: camera = IMU frame (T_cam_imu = I), relative to the
first pose, positions multiplied by SCALE. Used by scripts/demo.sh to feed `splinecal align`.
usage: up_to_scale_camera.py GROUNDTRUTH.csv SCALE EVERY_NTH > camera.txt"""
import sys


def qmul(a, b):
    aw, ax, ay, az = a
    bw, bx, by, bz = b
    return (aw * bw - ax * bx - ay * by - az * bz, aw * bx + ax * bw + ay * bz - az * by,
            aw * by - ax * bz + ay * bw + az * bx, aw * bz + ax * by - ay * bx + az * bw)


def rotate(q, v):
    w, x, y, z = qmul(qmul(q, (0.0, *v)), (q[0], -q[1], -q[2], -q[3]))
    return (x, y, z)


rows = [l.split(',') for l in open(sys.argv[1]) if l.strip() and not l.startswith('#')]
scale, every = float(sys.argv[2]), int(sys.argv[3])
t0 = None
for i, r in enumerate(rows):
    if i % every:
        continue
    t_ns, p, q = int(r[0]), tuple(map(float, r[1:4])), tuple(map(float, r[4:8]))
    if t0 is None:
        t0, p0, q0_inv = t_ns, p, (q[0], -q[1], -q[2], -q[3])
    rel_q = qmul(q0_inv, q)
    rel_p = rotate(q0_inv, tuple(a - b for a, b in zip(p, p0)))
    print('%d.%09d %.17g %.17g %.17g %.17g %.17g %.17g %.17g' %
          (t_ns // 10**9, t_ns % 10**9, *(scale * c for c in rel_p), rel_q[1], rel_q[2], rel_q[3],
           rel_q[0]))
# On stderr: the true gravity in the first camera frame, R_w_c0^T g_w, for comparison.
qc = (rows[0] and tuple(map(float, rows[0][4:8])))
g_c0 = rotate((qc[0], -qc[1], -qc[2], -qc[3]), (0.0, 0.0, -9.81))
print('true_scale %.9g true_gravity_c0 %.9g %.9g %.9g' % (1.0 / scale, *g_c0), file=sys.stderr)
