// From a Jacobian in a pose's right tangent to the Jacobian Ceres wants: with respect to the
// ambient pose block {px, py, pz, qx, qy, qz, qw} (ceres/cost_function.h: jacobians[i][r * 7 + c]
// = d residual[r] / d block[c]).
//
// A cost function that reads its pose with PoseFromBlock (lie/se3_manifold.h: translation as
// is, quaternion normalised) depends on the block through the right tangent d of
// T Exp(d) as
//
//   d rho / d t_block = R^T,   d phi / d q_block = 2 [w I - [v]x, -v]   (q = (v, w) unit)
//
// which is exactly SE3Manifold::MinusJacobian (its rows kill the radial direction of q, as the
// normalisation does). So
//
//   J_ambient = J_tangent * MinusJacobian(x),
//
// the true derivative of the cost function with respect to its block, and Ceres' own chain rule
// J_ambient * PlusJacobian(x) gives back J_tangent (MinusJacobian * PlusJacobian = I). No
// shortcut through a fake "identity" manifold Jacobian: ceres::GradientChecker and numeric
// differentiation agree with these Jacobians.
#ifndef SPLINECAL_ESTIMATION_DETAIL_POSE_BLOCK_JACOBIAN_H_
#define SPLINECAL_ESTIMATION_DETAIL_POSE_BLOCK_JACOBIAN_H_

#include <Eigen/Core>

#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace internal {

// The two non-zero blocks of SE3Manifold::MinusJacobian at a pose block.
struct PoseBlockLift {
  Eigen::Matrix3d Rt;                   // R^T (translation columns)
  Eigen::Matrix<double, 3, 4> dphi_dq;  // 2 [w I - [v]x, -v] (quaternion columns)
};

inline PoseBlockLift MakePoseBlockLift(const double* pose_block) {
  const SE3d pose = PoseFromBlock(pose_block);
  PoseBlockLift lift;
  lift.Rt = pose.so3().matrix().transpose();
  lift.dphi_dq = QuaternionRightMinusJacobian(pose.so3().quaternion());
  return lift;
}

// A Jacobian with respect to one pose block: `rows` rows of 7 (row-major) at `jacobian`.
using AmbientPoseJacobian = Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>>;
inline AmbientPoseJacobian AmbientPoseRows(double* jacobian, Eigen::Index rows) {
  return AmbientPoseJacobian(jacobian, rows, 7);
}

// Writes J_tangent (rows x 6, columns [rho | phi]) lifted to the ambient block as `rows` rows
// of 7 (row-major) at `jacobian`.
template <typename Derived>
void LiftPoseJacobian(const Eigen::MatrixBase<Derived>& J_tangent,
                      const PoseBlockLift& lift,
                      double* jacobian) {
  auto J = AmbientPoseRows(jacobian, J_tangent.rows());
  J.template leftCols<3>().noalias() = J_tangent.template leftCols<3>() * lift.Rt;
  J.template rightCols<4>().noalias() = J_tangent.template rightCols<3>() * lift.dphi_dq;
}

// The same for rows whose translation columns are zero (gyro residuals): J_phi is rows x 3.
template <typename Derived>
void LiftRotationOnlyPoseJacobian(const Eigen::MatrixBase<Derived>& J_phi,
                                  const PoseBlockLift& lift,
                                  double* jacobian) {
  auto J = AmbientPoseRows(jacobian, J_phi.rows());
  J.template leftCols<3>().setZero();
  J.template rightCols<4>().noalias() = J_phi * lift.dphi_dq;
}

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_POSE_BLOCK_JACOBIAN_H_
