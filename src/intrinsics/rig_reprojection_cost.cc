#include "splinecal/intrinsics/rig_reprojection_cost.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

RigViewCostFunction::RigViewCostFunction(const RigViewOptions& settings,
                                         std::vector<TargetCornerObservation> corners)
    : settings_(settings), corners_(std::move(corners)) {
  set_num_residuals(2 * static_cast<int>(corners_.size()));
  mutable_parameter_block_sizes()->push_back(kPoseBlockSize);
  mutable_parameter_block_sizes()->push_back(kNumIntrinsics);
  if (settings_.has_extrinsic) mutable_parameter_block_sizes()->push_back(kPoseBlockSize);
  if (settings_.shape.size() > 0) {
    mutable_parameter_block_sizes()->push_back(settings_.shape.size());
  }
  if (settings_.shape.per_view_inset()) mutable_parameter_block_sizes()->push_back(1);
}

bool RigViewCostFunction::Evaluate(double const* const* parameters,
                                   double* residuals,
                                   double** jacobians) const {
  Camera camera = settings_.model;
  camera.set_intrinsics(Eigen::Map<const IntrinsicsVector>(parameters[1]));
  const SE3d T_c0_t = PoseFromBlock(parameters[0]);
  const SE3d T_cn_c0 = settings_.has_extrinsic ? PoseFromBlock(parameters[2]) : SE3d();
  const Eigen::Matrix3d R_cn_c0 = T_cn_c0.so3().matrix();
  const Eigen::Matrix3d R_cn_t = R_cn_c0 * T_c0_t.so3().matrix();

  double* J_target = jacobians != nullptr ? jacobians[0] : nullptr;
  double* J_intrinsics = jacobians != nullptr ? jacobians[1] : nullptr;
  double* J_extrinsic = jacobians != nullptr && settings_.has_extrinsic ? jacobians[2] : nullptr;
  const int shape_size = settings_.shape.size();
  const int shape_index = settings_.has_extrinsic ? 3 : 2;
  const double* c = shape_size > 0 ? parameters[shape_index] : nullptr;
  double* J_shape = jacobians != nullptr && shape_size > 0 ? jacobians[shape_index] : nullptr;
  const bool has_inset = settings_.shape.per_view_inset();
  const double inset = has_inset ? parameters[shape_index + 1][0] : 0.0;
  double* J_inset = jacobians != nullptr && has_inset ? jacobians[shape_index + 1] : nullptr;
  const bool any_jacobian = J_intrinsics != nullptr || J_target != nullptr ||
                            J_extrinsic != nullptr || J_shape != nullptr || J_inset != nullptr;
  internal::PoseBlockLift target_lift, extrinsic_lift;
  if (J_target != nullptr) target_lift = internal::MakePoseBlockLift(parameters[0]);
  if (J_extrinsic != nullptr) extrinsic_lift = internal::MakePoseBlockLift(parameters[2]);

  const double inv_sigma = 1.0 / settings_.sigma_px;
  const double k = settings_.huber_px / settings_.sigma_px;
  for (size_t i = 0; i < corners_.size(); ++i) {
    const int row = 2 * static_cast<int>(i);
    const Eigen::Vector3d p_t = settings_.shape.Deform(corners_[i].p_t, c, inset);
    const Eigen::Vector3d x_c0 = T_c0_t * p_t;
    const Eigen::Vector3d x_c = T_cn_c0 * x_c0;
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 3> J_pi;
    Eigen::Matrix<double, 2, kNumIntrinsics> J_uv_intrinsics;
    const bool projected = camera.Project(x_c,
                                          &uv,
                                          any_jacobian ? &J_pi : nullptr,
                                          J_intrinsics != nullptr ? &J_uv_intrinsics : nullptr);
    if (!projected) {
      // Outside the model's valid region: no information from this corner at these values.
      residuals[row] = residuals[row + 1] = 0.0;
      if (J_intrinsics != nullptr) {
        std::fill(
            J_intrinsics + row * kNumIntrinsics, J_intrinsics + (row + 2) * kNumIntrinsics, 0.0);
      }
      if (J_target != nullptr) std::fill(J_target + 7 * row, J_target + 7 * (row + 2), 0.0);
      if (J_extrinsic != nullptr) {
        std::fill(J_extrinsic + 7 * row, J_extrinsic + 7 * (row + 2), 0.0);
      }
      if (J_shape != nullptr) {
        std::fill(J_shape + shape_size * row, J_shape + shape_size * (row + 2), 0.0);
      }
      if (J_inset != nullptr) J_inset[row] = J_inset[row + 1] = 0.0;
      continue;
    }
    Eigen::Vector2d r = (uv - corners_[i].uv) * inv_sigma;
    Eigen::Matrix2d S;
    internal::RobustifyPoint(k, &r, any_jacobian ? &S : nullptr);
    residuals[row] = r.x();
    residuals[row + 1] = r.y();
    if (!any_jacobian) continue;
    const Eigen::Matrix2d F = inv_sigma * S;
    if (J_intrinsics != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 2, kNumIntrinsics, Eigen::RowMajor>>(
          J_intrinsics + row * kNumIntrinsics) = F * J_uv_intrinsics;
    }
    const Eigen::Matrix<double, 2, 3> FJ = F * J_pi;
    if (J_target != nullptr) {
      Eigen::Matrix<double, 2, 6> J_tangent;
      J_tangent.leftCols<3>() = FJ * R_cn_t;
      J_tangent.rightCols<3>() = -FJ * R_cn_t * Hat(p_t);
      internal::LiftPoseJacobian(J_tangent, target_lift, J_target + 7 * row);
    }
    if (J_extrinsic != nullptr) {
      Eigen::Matrix<double, 2, 6> J_tangent;
      J_tangent.leftCols<3>() = FJ * R_cn_c0;
      J_tangent.rightCols<3>() = -FJ * R_cn_c0 * Hat(x_c0);
      internal::LiftPoseJacobian(J_tangent, extrinsic_lift, J_extrinsic + 7 * row);
    }
    if (J_shape != nullptr || J_inset != nullptr) {
      // The shape moves the point by D c in the target frame (D = e_z b^T out of plane), the
      // per-view inset by its column D_d d_v: d x_c / d c = R_cn_t D, d x_c / d d_v = R_cn_t D_d.
      const TargetDisplacement D = settings_.shape.Displacement(corners_[i].p_t);
      const Eigen::Matrix<double, 2, 3> FJR = FJ * R_cn_t;
      if (J_shape != nullptr) {
        Eigen::Map<Eigen::Matrix<double, 2, Eigen::Dynamic, Eigen::RowMajor>>(
            J_shape + shape_size * row, 2, shape_size) = FJR * D.leftCols(shape_size);
      }
      if (J_inset != nullptr) {
        Eigen::Map<Eigen::Vector2d>(J_inset + row) = FJR * D.col(TargetShape::kInsetColumn);
      }
    }
  }
  return true;
}

std::vector<Eigen::Vector2d> RigViewErrors(const Camera& camera,
                                           const SE3d& T_cn_t,
                                           const std::vector<TargetCornerObservation>& corners) {
  std::vector<Eigen::Vector2d> errors;
  errors.reserve(corners.size());
  for (const TargetCornerObservation& corner : corners) {
    Eigen::Vector2d uv;
    if (camera.Project(T_cn_t * corner.p_t, &uv)) {
      errors.push_back(uv - corner.uv);
    } else {
      errors.push_back(Eigen::Vector2d::Constant(std::numeric_limits<double>::quiet_NaN()));
    }
  }
  return errors;
}

}  // namespace splinecal
