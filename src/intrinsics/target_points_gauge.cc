#include "splinecal/intrinsics/target_points_gauge.h"

#include "splinecal/lie/so3.h"

namespace splinecal {

Eigen::MatrixXd TargetSimilarityGenerators(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  if (!points.empty()) mean /= static_cast<double>(points.size());
  Eigen::MatrixXd G(3 * points.size(), 7);
  for (size_t i = 0; i < points.size(); ++i) {
    const Eigen::Vector3d q = points[i] - mean;
    G.block<3, 3>(3 * i, 0).setIdentity();
    G.block<3, 3>(3 * i, 3) = -Hat(q);
    G.block<3, 1>(3 * i, 6) = q;
  }
  return G;
}

TargetPointsGaugeCost::TargetPointsGaugeCost(const std::vector<Eigen::Vector3d>& points) {
  set_num_residuals(7);
  const Eigen::MatrixXd G = TargetSimilarityGenerators(points);
  for (size_t i = 0; i < points.size(); ++i) {
    generators_t_.push_back(G.middleRows<3>(3 * i).transpose() / kTargetGaugeStdM);
    mutable_parameter_block_sizes()->push_back(3);
  }
}

bool TargetPointsGaugeCost::Evaluate(double const* const* parameters,
                                     double* residuals,
                                     double** jacobians) const {
  Eigen::Map<Eigen::Matrix<double, 7, 1>> r(residuals);
  r.setZero();
  for (size_t i = 0; i < generators_t_.size(); ++i) {
    r += generators_t_[i] * Eigen::Map<const Eigen::Vector3d>(parameters[i]);
    if (jacobians != nullptr && jacobians[i] != nullptr) {
      Eigen::Map<Eigen::Matrix<double, 7, 3, Eigen::RowMajor>> J(jacobians[i]);
      J = generators_t_[i];
    }
  }
  return true;
}

}  // namespace splinecal
