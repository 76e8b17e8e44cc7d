#!/usr/bin/env python3
"""How much of the rotation between two calibrations' T_cam_imu is only the two intrinsics'
definitions of the camera frame? docs/calibrate.md, "Why: the principal point".

A camera model maps pixels to rays in its own camera frame; two models fitted to the same lens
(another principal point, another projection) put the same pixel's ray in frames turned against
each other. Over a grid of pixels, this finds the rotation R_ray that best takes model a's rays
to model b's (Wahba's problem, solved by SVD), and compares it with the rotation between the two
calibrations' camera frames as their T_cam_imu say, R_b_a = R_b_imu R_a_imu^T. What is left,
R_ray^T R_b_a, is where the two calibrations disagree on the IMU-frame direction of each pixel.

    python3 docs/experiments/ray_alignment.py A/camchain-imucam.yaml B/camchain-imucam.yaml

Reads Kalibr camchains with pinhole-radtan or ds (double sphere) cameras. Needs numpy and yaml.
"""
import sys

import numpy as np
import yaml


def unproject_ds(p, uv):
    xi, alpha, fu, fv, pu, pv = p
    mx, my = (uv[:, 0] - pu) / fu, (uv[:, 1] - pv) / fv
    r2 = mx * mx + my * my
    valid = (alpha <= 0.5) | (r2 <= 1.0 / (2.0 * alpha - 1.0))
    mz = (1 - alpha * alpha * r2) / (alpha * np.sqrt(np.maximum(0, 1 - (2 * alpha - 1) * r2)) + 1 - alpha)
    k = (mz * xi + np.sqrt(mz * mz + (1 - xi * xi) * r2)) / (mz * mz + r2)
    ray = np.stack([k * mx, k * my, k * mz - xi], 1)
    return ray / np.linalg.norm(ray, axis=1)[:, None], valid


def unproject_radtan(p, d, uv):
    fu, fv, pu, pv = p
    k1, k2, p1, p2 = d
    xd, yd = (uv[:, 0] - pu) / fu, (uv[:, 1] - pv) / fv
    x, y = xd.copy(), yd.copy()
    for _ in range(200):  # fixed point of the distortion
        r2 = x * x + y * y
        radial = 1 + k1 * r2 + k2 * r2 * r2
        x = (xd - (2 * p1 * x * y + p2 * (r2 + 2 * x * x))) / radial
        y = (yd - (p1 * (r2 + 2 * y * y) + 2 * p2 * x * y)) / radial
    ray = np.stack([x, y, np.ones_like(x)], 1)
    return ray / np.linalg.norm(ray, axis=1)[:, None], np.ones(len(x), bool)


def unproject(camera, uv):
    if camera["camera_model"] == "ds":
        return unproject_ds(camera["intrinsics"], uv)
    return unproject_radtan(camera["intrinsics"], camera["distortion_coeffs"], uv)


def wahba(a, b):
    """R minimising sum |R a_i - b_i|^2."""
    u, _, vt = np.linalg.svd(a.T @ b)
    return vt.T @ np.diag([1, 1, np.linalg.det(vt.T @ u.T)]) @ u.T


def log_deg(R):
    angle = np.arccos(np.clip((np.trace(R) - 1) / 2, -1, 1))
    if angle < 1e-12:
        return np.zeros(3)
    axis = np.array([R[2, 1] - R[1, 2], R[0, 2] - R[2, 0], R[1, 0] - R[0, 1]]) / (2 * np.sin(angle))
    return np.degrees(angle * axis)


def main():
    a, b = (yaml.safe_load(open(path)) for path in sys.argv[1:3])
    for cam in ("cam0", "cam1"):
        ca, cb = a[cam], b[cam]
        width, height = ca["resolution"]
        u, v = np.meshgrid(np.linspace(10, width - 10, 60), np.linspace(10, height - 10, 40))
        grid = np.stack([u.ravel(), v.ravel()], 1)
        R_a = np.array(ca["T_cam_imu"])[:3, :3]
        R_b_a = np.array(cb["T_cam_imu"])[:3, :3] @ R_a.T
        for name, pixels in (("whole image", grid),
                             ("centre half", grid[(abs(grid[:, 0] - width / 2) < width / 4) &
                                                  (abs(grid[:, 1] - height / 2) < height / 4)])):
            ra, ok_a = unproject(ca, pixels)
            rb, ok_b = unproject(cb, pixels)
            ok = ok_a & ok_b
            R_ray = wahba(ra[ok], rb[ok])
            after = np.degrees(np.arccos(np.clip(np.sum((ra[ok] @ R_ray.T) * rb[ok], 1), -1, 1)))
            left_imu = R_a.T @ log_deg(R_ray.T @ R_b_a)
            print(f"{cam}, {name}: camera frames per T_cam_imu {np.round(log_deg(R_b_a), 3)} deg "
                  f"(camera a's axes), {np.round(R_a.T @ log_deg(R_b_a), 3)} deg in the IMU "
                  f"frame; ray alignment {np.round(log_deg(R_ray), 3)} deg, rays "
                  f"{np.sqrt(np.mean(after ** 2)) * 3600:.0f} arcsec RMS apart after it; left, "
                  f"in the IMU frame: {np.round(left_imu, 3)} deg")


if __name__ == "__main__":
    main()
