#include "splinecal/estimation/bias_costs.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

#include "testing/autodiff_costs.h"

namespace splinecal {
namespace {

// Closed-form comparisons in double: a few ulps of O(1) numbers.
constexpr double kExactTolerance = 1e-12;
// The midpoint rule with 200000 steps integrates the degree-4 products to ~1e-11.
constexpr double kQuadratureTolerance = 1e-9;
constexpr double kGradientCheckerPrecision = 1e-8;

TEST(BiasSplineWeights, AreTheUniformCubicBSplineBasis) {
  for (double u : {0.0, 0.25, 0.5, 0.9, 1.0}) {
    const std::array<double, 4> w = BiasSplineWeights(u);
    EXPECT_NEAR(w[0], std::pow(1.0 - u, 3) / 6.0, kExactTolerance);
    EXPECT_NEAR(w[1], (3.0 * u * u * u - 6.0 * u * u + 4.0) / 6.0, kExactTolerance);
    EXPECT_NEAR(w[2], (-3.0 * u * u * u + 3.0 * u * u + 3.0 * u + 1.0) / 6.0, kExactTolerance);
    EXPECT_NEAR(w[3], u * u * u / 6.0, kExactTolerance);
    EXPECT_NEAR(w[0] + w[1] + w[2] + w[3], 1.0, kExactTolerance);
  }
}

TEST(BiasRandomWalkSqrtInformation, SquaresToTheIntegralOfTheDerivativeProducts) {
  const Eigen::Matrix<double, 3, 4> S = BiasRandomWalkSqrtInformation();
  // M by a fine midpoint rule from the closed-form derivatives of the basis.
  const int steps = 200000;
  Eigen::Matrix4d M = Eigen::Matrix4d::Zero();
  for (int k = 0; k < steps; ++k) {
    const double u = (k + 0.5) / steps;
    const Eigen::Vector4d d(-0.5 * (1.0 - u) * (1.0 - u),
                            (9.0 * u * u - 12.0 * u) / 6.0,
                            (-9.0 * u * u + 6.0 * u + 3.0) / 6.0,
                            0.5 * u * u);
    M += d * d.transpose() / steps;
  }
  EXPECT_LE((S.transpose() * S - M).cwiseAbs().maxCoeff(), kQuadratureTolerance);
  // A constant bias costs nothing.
  EXPECT_LE((S * Eigen::Vector4d::Ones()).norm(), kExactTolerance);
}

TEST(BiasRandomWalkCostFunction, RampCostsTheWienerPathIntegral) {
  // c_m = m v: the spline is the line b(t) = v t / db, so int |b'|^2 dt over one segment is
  // |v|^2 / db and the cost 1/2 |r|^2 = |v|^2 / (2 sigma^2 db).
  const double db = 0.5;
  const double sigma = 3e-3;
  const Eigen::Vector3d v(1e-3, -2e-3, 0.5e-3);
  std::array<Eigen::Vector3d, 4> c;
  for (int m = 0; m < 4; ++m) c[m] = (m + 7.0) * v;
  const double* parameters[4] = {c[0].data(), c[1].data(), c[2].data(), c[3].data()};
  const BiasRandomWalkCostFunction cost(db, sigma);
  Eigen::Matrix<double, 9, 1> r;
  ASSERT_TRUE(cost.Evaluate(parameters, r.data(), nullptr));
  EXPECT_NEAR(r.squaredNorm(),
              v.squaredNorm() / (sigma * sigma * db),
              1e-12 * v.squaredNorm() / (sigma * sigma * db));
}

TEST(BiasRandomWalkCostFunction, AnalyticMatchesAutoDiffAndGradientChecker) {
  std::mt19937 rng(3);
  std::normal_distribution<double> normal(0.0, 0.1);
  std::array<Eigen::Vector3d, 4> c;
  for (auto& ci : c) ci = Eigen::Vector3d(normal(rng), normal(rng), normal(rng));
  const double* parameters[4] = {c[0].data(), c[1].data(), c[2].data(), c[3].data()};
  const BiasRandomWalkCostFunction analytic(1.0, 2e-3);
  ceres::AutoDiffCostFunction<testing::BiasRandomWalkResidual, 9, 3, 3, 3, 3> autodiff(
      new testing::BiasRandomWalkResidual(1.0, 2e-3));
  std::array<std::array<double, 27>, 4> J_a;
  std::array<std::array<double, 27>, 4> J_b;
  double* jacobians_a[4] = {J_a[0].data(), J_a[1].data(), J_a[2].data(), J_a[3].data()};
  double* jacobians_b[4] = {J_b[0].data(), J_b[1].data(), J_b[2].data(), J_b[3].data()};
  std::array<double, 9> r_a;
  std::array<double, 9> r_b;
  ASSERT_TRUE(analytic.Evaluate(parameters, r_a.data(), jacobians_a));
  ASSERT_TRUE(autodiff.Evaluate(parameters, r_b.data(), jacobians_b));
  for (int k = 0; k < 9; ++k) EXPECT_NEAR(r_a[k], r_b[k], 1e-9 * std::max(1.0, std::abs(r_b[k])));
  for (int j = 0; j < 4; ++j) {
    for (int k = 0; k < 27; ++k) {
      EXPECT_NEAR(J_a[j][k], J_b[j][k], 1e-9 * std::max(1.0, std::abs(J_b[j][k])));
    }
  }
  const std::vector<const ceres::Manifold*> no_manifolds(4, nullptr);
  ceres::GradientChecker checker(&analytic, &no_manifolds, ceres::NumericDiffOptions());
  ceres::GradientChecker::ProbeResults results;
  EXPECT_TRUE(checker.Probe(parameters, kGradientCheckerPrecision, &results)) << results.error_log;
}

}  // namespace
}  // namespace splinecal
