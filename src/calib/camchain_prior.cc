#include "splinecal/calib/camchain_prior.h"

#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <utility>

#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {

CamchainPriorCostFunction::CamchainPriorCostFunction(std::vector<int> intrinsics,
                                                     const IntrinsicsVector& reference,
                                                     std::optional<SE3d> T_cn_cnm1,
                                                     const Eigen::MatrixXd& covariance)
    : intrinsics_(std::move(intrinsics)), reference_(reference), T_cn_cnm1_(T_cn_cnm1) {
  const int n = static_cast<int>(intrinsics_.size()) + (T_cn_cnm1_ ? 6 : 0);
  CHECK_GT(n, 0);
  CHECK_EQ(covariance.rows(), n);
  CHECK_EQ(covariance.cols(), n);
  const Eigen::LLT<Eigen::MatrixXd> llt(covariance);
  CHECK(llt.info() == Eigen::Success) << "the prior's covariance is not positive definite";
  whitening_ = llt.matrixL().solve(Eigen::MatrixXd::Identity(n, n));
  set_num_residuals(n);
  if (!intrinsics_.empty()) mutable_parameter_block_sizes()->push_back(kNumIntrinsics);
  if (T_cn_cnm1_) {
    mutable_parameter_block_sizes()->push_back(7);
    mutable_parameter_block_sizes()->push_back(7);
  }
}

bool CamchainPriorCostFunction::Evaluate(double const* const* parameters,
                                         double* residuals,
                                         double** jacobians) const {
  const int m = static_cast<int>(intrinsics_.size());
  const int n = num_residuals();
  Eigen::VectorXd difference(n);
  int block = 0;
  if (m > 0) {
    const Eigen::Map<const IntrinsicsVector> theta(parameters[block++]);
    for (int j = 0; j < m; ++j) difference(j) = theta(intrinsics_[j]) - reference_(intrinsics_[j]);
  }
  Matrix6d J_xi_a = Matrix6d::Zero();  // d xi / d a (T_cn_imu's right tangent)
  if (T_cn_cnm1_) {
    const SE3d T_cn_imu = PoseFromBlock(parameters[block]);
    const SE3d T_cnm1_imu = PoseFromBlock(parameters[block + 1]);
    const SE3d E = T_cn_cnm1_->inverse() * T_cn_imu * T_cnm1_imu.inverse();
    const Vector6d xi = E.Log();
    difference.tail<6>() = xi;
    if (jacobians != nullptr) J_xi_a = RightJacobianInverseSE3(xi) * T_cnm1_imu.Adj();
  }
  Eigen::Map<Eigen::VectorXd>(residuals, n) = whitening_ * difference;
  if (jacobians == nullptr) return true;
  block = 0;
  if (m > 0) {
    if (jacobians[block] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, kNumIntrinsics, Eigen::RowMajor>> J(
          jacobians[block], n, kNumIntrinsics);
      J.setZero();
      for (int j = 0; j < m; ++j) J.col(intrinsics_[j]) = whitening_.col(j);
    }
    ++block;
  }
  if (T_cn_cnm1_) {
    const Eigen::MatrixXd J_a = whitening_.rightCols<6>() * J_xi_a;
    for (int k = 0; k < 2; ++k, ++block) {
      if (jacobians[block] == nullptr) continue;
      const Eigen::MatrixXd J_tangent = k == 0 ? J_a : Eigen::MatrixXd(-J_a);
      internal::LiftPoseJacobian(
          J_tangent, internal::MakePoseBlockLift(parameters[block]), jacobians[block]);
    }
  }
  return true;
}

}  // namespace splinecal
