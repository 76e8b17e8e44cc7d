// Camera-IMU rotation from relative rotations (the rotation part of hand-eye calibration).
//
// What this header implements
//   For frame pairs k (consecutive camera frames), the camera's relative rotation
//   Rc_k = R_ck_ck+1 (from the camera poses) and the IMU's Rs_k = R_sk_sk+1 (the preintegrated
//   gyro) satisfy, with X = R_cam_imu = R_c_s (docs/conventions.md "Camera, time offset, rolling
//   shutter": T_cam_imu maps IMU points into the camera):
//
//     R_c0_sk = R_c0_ck X   =>   Rs_k = X^T Rc_k X   <=>   Rc_k X = X Rs_k
//
//   In quaternions qc_k (x) qx = qx (x) qs_k, i.e. (L(qc_k) - R(qs_k)) qx = 0 with L, R the left
//   and right quaternion-product matrices [Qin18, Sec. V-A]. Stacking every pair gives a 4N x 4
//   system whose null vector is qx: the eigenvector of the smallest eigenvalue of the 4x4 normal
//   matrix (the squared singular values).
//
// Degeneracy, in plain numbers: for one pair with rotation angle t about the axis a, L - R has
//   two singular values 2 sin(t/2) and a two-dimensional null space {qx, qx (x) (0, a)}. Stacked,
//   the singular values sigma_1 >= sigma_2 >= sigma_3 >= sigma_4 (= 0 at the solution) satisfy
//   sigma_i^2 = 4 (n_j + n_k) for the eigenvalues n_1 >= n_2 >= n_3 of the axis matrix
//   N = sum_k sin^2(t_k/2) a_k a_k^T, so
//
//     second_axis_ratio = sigma_3 / sigma_1 = sqrt((n_2 + n_3) / (n_1 + n_2))
//
//   is 0 when every rotation is about the same axis (the rotation about that axis is then
//   unobservable) and about 1 for rotation spread over all axes. sigma_3 ~ the root-sum-square of
//   the rotation angles [rad] about the weaker axes.
//
// References: [Qin18] T. Qin, P. Li, S. Shen, VINS-Mono, IEEE T-RO 2018 (Sec. V-A, extrinsic
// rotation); [Sola18] quaternion products.
#ifndef SPLINECAL_VIO_HAND_EYE_H_
#define SPLINECAL_VIO_HAND_EYE_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/lie/so3.h"

namespace splinecal {

struct HandEyeOptions {
  // Refuse when sigma_3 / sigma_1 is below this: with 0.1 the weaker axes carry under 1% of the
  // rotation energy, and a rotation error about the main axis is then ~10x less constrained
  // than about the others.
  double min_second_axis_ratio = 0.1;
  // Refuse when sigma_3 [~rad, root-sum-square of the rotation about the weaker axes] is below
  // this: 0.05 rad = 2.9 deg in total is under what gyro noise and camera pose noise (~0.1 deg
  // per frame) can resolve over a window of 100 frames.
  double min_second_axis_rotation_rad = 0.05;
};

struct HandEyeRotationResult {
  bool ok = false;
  std::string message;  // why it was refused (plain words), empty when ok
  SO3d R_cam_imu;       // X = R_c_s
  Eigen::Vector4d singular_values = Eigen::Vector4d::Zero();  // descending
  double second_axis_ratio = 0.0;                             // sigma_3 / sigma_1
};

// Solves Rc_k X = X Rs_k for X = R_cam_imu over all pairs (R_ck_ck1[k], R_sk_sk1[k]); the two
// vectors must have the same size (CHECKed). Returns ok = false with a message for fewer than 2
// pairs or a degenerate motion (see the file comment); R_cam_imu is the least-squares solution
// either way.
HandEyeRotationResult EstimateHandEyeRotation(const std::vector<SO3d>& R_ck_ck1,
                                              const std::vector<SO3d>& R_sk_sk1,
                                              const HandEyeOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_VIO_HAND_EYE_H_
