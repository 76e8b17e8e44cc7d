#include "splinecal/estimation/bias_costs.h"

#include <glog/logging.h>

#include <Eigen/Eigenvalues>
#include <cmath>

namespace splinecal {

Eigen::Matrix<double, 3, 4> BiasRandomWalkSqrtInformation() {
  // 3-point Gauss-Legendre on [0, 1]: nodes 1/2 -+ sqrt(3/5)/2, 1/2; weights 5/18, 8/18, 5/18.
  const double offset = 0.5 * std::sqrt(0.6);
  const double nodes[3] = {0.5 - offset, 0.5, 0.5 + offset};
  const double weights[3] = {5.0 / 18.0, 8.0 / 18.0, 5.0 / 18.0};
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (int q = 0; q < 3; ++q) {
    // B_j' = Bt_j' - Bt_{j+1}' (u-derivatives of the cumulative basis).
    const Eigen::Vector4d dbt = CumulativeBasis<1>(nodes[q]);
    const Eigen::Vector4d db(dbt[0] - dbt[1], dbt[1] - dbt[2], dbt[2] - dbt[3], dbt[3]);
    M += weights[q] * db * db.transpose();
  }
  // M = V diag(lambda) V^T, eigenvalues ascending; lambda_0 = 0 (constant control points).
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eigen(M);
  CHECK_EQ(eigen.info(), Eigen::Success);
  Eigen::Matrix<double, 3, 4> S;
  for (int m = 0; m < 3; ++m) {
    const double lambda = eigen.eigenvalues()[m + 1];
    CHECK_GT(lambda, 1e-6) << "bias random-walk information has rank < 3";
    S.row(m) = std::sqrt(lambda) * eigen.eigenvectors().col(m + 1).transpose();
  }
  return S;
}

BiasRandomWalkCostFunction::BiasRandomWalkCostFunction(double knot_spacing_s,
                                                       double random_walk_density) {
  CHECK(knot_spacing_s > 0.0 && std::isfinite(knot_spacing_s));
  CHECK(random_walk_density > 0.0 && std::isfinite(random_walk_density));
  const Eigen::Matrix<double, 3, 4> S =
      BiasRandomWalkSqrtInformation() / (random_walk_density * std::sqrt(knot_spacing_s));
  jacobian_.setZero();
  for (int m = 0; m < 3; ++m) {
    for (int j = 0; j < 4; ++j) {
      jacobian_.block<3, 3>(3 * m, 3 * j) = S(m, j) * Eigen::Matrix3d::Identity();
    }
  }
}

bool BiasRandomWalkCostFunction::Evaluate(double const* const* parameters,
                                          double* residuals,
                                          double** jacobians) const {
  Eigen::Matrix<double, 12, 1> c;
  for (int j = 0; j < 4; ++j)
    c.segment<3>(3 * j) = Eigen::Map<const Eigen::Vector3d>(parameters[j]);
  Eigen::Map<Eigen::Matrix<double, 9, 1>> r(residuals);
  r = jacobian_ * c;
  if (jacobians == nullptr) return true;
  for (int j = 0; j < 4; ++j) {
    if (jacobians[j] == nullptr) continue;
    Eigen::Map<Eigen::Matrix<double, 9, 3, Eigen::RowMajor>> J(jacobians[j]);
    J = jacobian_.block<9, 3>(0, 3 * j);
  }
  return true;
}

}  // namespace splinecal
