#include "splinecal/intrinsics/target_points_gauge.h"

#include "splinecal/lie/so3.h"

namespace splinecal {

TargetPointsGaugeCost::TargetPointsGaugeCost(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : points) mean += p;
  if (!points.empty()) mean /= static_cast<double>(points.size());
  set_num_residuals(7);
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d q = p - mean;
    Eigen::Matrix<double, 3, 7> G;
    G.leftCols<3>().setIdentity();
    G.middleCols<3>(3) = -Hat(q);
    G.col(6) = q;
    generators_t_.push_back(G.transpose() / kTargetGaugeStdM);
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
