#include "splinecal/vio/hand_eye.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// q as a 4-vector (w, x, y, z), folded onto w >= 0 (q and -q are the same rotation; the hand-eye
// equation needs both sides of a pair on the same sheet: conjugation keeps w, so for rotations
// below pi both have the same sign of w).
Eigen::Vector4d FoldedWxyz(const SO3d& R) {
  const Eigen::Quaterniond& q = R.quaternion();
  Eigen::Vector4d v(q.w(), q.x(), q.y(), q.z());
  return q.w() < 0.0 ? Eigen::Vector4d(-v) : v;
}

// Left and right product matrices: p (x) q = L(p) q = R(q) p, vectors (w, x, y, z).
//   L(p) = [[w, -v^T], [v, w I + [v]x]],   R(q) = [[w, -v^T], [v, w I - [v]x]]   ([Sola18])
Eigen::Matrix4d LeftProductMatrix(const Eigen::Vector4d& p) {
  Eigen::Matrix4d m;
  m(0, 0) = p(0);
  m.block<1, 3>(0, 1) = -p.tail<3>().transpose();
  m.block<3, 1>(1, 0) = p.tail<3>();
  m.block<3, 3>(1, 1) = p(0) * Eigen::Matrix3d::Identity() + Hat(p.tail<3>());
  return m;
}

Eigen::Matrix4d RightProductMatrix(const Eigen::Vector4d& q) {
  Eigen::Matrix4d m;
  m(0, 0) = q(0);
  m.block<1, 3>(0, 1) = -q.tail<3>().transpose();
  m.block<3, 1>(1, 0) = q.tail<3>();
  m.block<3, 3>(1, 1) = q(0) * Eigen::Matrix3d::Identity() - Hat(q.tail<3>());
  return m;
}

}  // namespace

HandEyeRotationResult EstimateHandEyeRotation(const std::vector<SO3d>& R_ck_ck1,
                                              const std::vector<SO3d>& R_sk_sk1,
                                              const HandEyeOptions& options) {
  CHECK_EQ(R_ck_ck1.size(), R_sk_sk1.size());
  HandEyeRotationResult result;
  // Normal matrix of the stacked (L(qc_k) - R(qs_k)) qx = 0.
  Eigen::Matrix4d normal = Eigen::Matrix4d::Zero();
  for (size_t k = 0; k < R_ck_ck1.size(); ++k) {
    const Eigen::Matrix4d block =
        LeftProductMatrix(FoldedWxyz(R_ck_ck1[k])) - RightProductMatrix(FoldedWxyz(R_sk_sk1[k]));
    normal.noalias() += block.transpose() * block;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(normal);
  const Eigen::Vector4d lambda = eigen.eigenvalues();  // ascending
  for (int i = 0; i < 4; ++i) result.singular_values(i) = std::sqrt(std::max(0.0, lambda(3 - i)));
  const Eigen::Vector4d x = eigen.eigenvectors().col(0);
  result.R_cam_imu = SO3d::FromQuaternion(Eigen::Quaterniond(x(0), x(1), x(2), x(3)));
  const double sigma_1 = result.singular_values(0);
  const double sigma_3 = result.singular_values(2);
  result.second_axis_ratio = sigma_1 > 0.0 ? sigma_3 / sigma_1 : 0.0;

  if (R_ck_ck1.size() < 2) {
    result.message =
        "cannot estimate the camera-IMU rotation from fewer than 2 pairs of camera frames";
    return result;
  }
  if (result.second_axis_ratio < options.min_second_axis_ratio ||
      sigma_3 < options.min_second_axis_rotation_rad) {
    result.message = StringPrintf(
        "cannot estimate the camera-IMU rotation: the rig rotated about one axis only "
        "(rotation about other axes: ratio %.3g, minimum %.3g; %.3g rad in total, "
        "minimum %.3g rad). Rotate about at least two axes, or give T_cam_imu with "
        "--camchain",
        result.second_axis_ratio,
        options.min_second_axis_ratio,
        sigma_3,
        options.min_second_axis_rotation_rad);
    return result;
  }
  result.ok = true;
  return result;
}

}  // namespace splinecal
