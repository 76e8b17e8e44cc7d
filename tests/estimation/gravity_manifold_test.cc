#include "splinecal/estimation/gravity_manifold.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "splinecal/units.h"
#include "testing/manifold_invariants.h"

namespace splinecal {
namespace {

using Vector = Eigen::VectorXd;
using testing::ExpectManifoldInvariantsHold;

// Ceres' invariant checks compare Plus/Minus round trips and Jacobians against numeric
// differentiation; 1e-9 leaves room for the numeric Jacobians' error (~1e-10 at |g| = 9.81).
constexpr double kInvariantTolerance = 1e-9;
constexpr double kG = 9.81;

std::vector<Eigen::Vector3d> TestDirections() {
  std::vector<Eigen::Vector3d> directions = {
      Eigen::Vector3d(0.0, 0.0, -1.0),  // the usual z-up world
      Eigen::Vector3d(0.0, 0.0, 1.0),
      Eigen::Vector3d(1.0, 0.0, 0.0),
      Eigen::Vector3d(0.0, -1.0, 0.0),
      // Where GravityTangentBasis switches its helper axis (|d_x| = |d_y|).
      Eigen::Vector3d(1.0, 1.0, 0.3).normalized(),
      Eigen::Vector3d(1.0, 1.0 + 1e-12, 0.3).normalized(),
  };
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int k = 0; k < 20; ++k) {
    directions.push_back(Eigen::Vector3d(normal(rng), normal(rng), normal(rng)).normalized());
  }
  return directions;
}

TEST(GravityManifold, InvariantsHoldForEveryDirection) {
  const GravityManifold manifold;
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const Eigen::Vector3d& d : TestDirections()) {
    const Vector x = kG * d;
    // Ceres' round-trip check is relative to |delta|: with |x| = 9.81 the ambient coordinates
    // carry ~1e-15 absolute rounding, so deltas below ~1e-6 rad fail it by construction.
    for (double size : {1e-5, 0.3, 2.5}) {
      Eigen::Vector2d w(normal(rng), normal(rng));
      w = size * w.normalized();
      Vector delta = w;
      Vector y(3);
      manifold.Plus(x.data(), delta.data(), y.data());
      ExpectManifoldInvariantsHold(manifold, x, delta, y, kInvariantTolerance);
    }
  }
}

TEST(GravityManifold, PlusKeepsTheNormAndMovesByTheTangentAngle) {
  const GravityManifold manifold;
  for (const Eigen::Vector3d& d : TestDirections()) {
    const Eigen::Vector3d x = kG * d;
    const Eigen::Vector2d w(0.3, -0.4);  // 0.5 rad
    Eigen::Vector3d y;
    ASSERT_TRUE(manifold.Plus(x.data(), w.data(), y.data()));
    EXPECT_NEAR(y.norm(), kG, 1e-12);
    EXPECT_NEAR(std::acos(x.normalized().dot(y.normalized())), 0.5, 1e-12);
  }
}

TEST(GravityManifold, MinusOfAPointNearTheAntipodeIsFinite) {
  const GravityManifold manifold;
  const Eigen::Vector3d x(0.0, 0.0, -kG);
  Eigen::Vector2d w(kPi - 1e-6, 0.0);
  Eigen::Vector3d y;
  ASSERT_TRUE(manifold.Plus(x.data(), w.data(), y.data()));
  Eigen::Vector2d back;
  ASSERT_TRUE(manifold.Minus(y.data(), x.data(), back.data()));
  EXPECT_NEAR((back - w).norm(), 0.0, 1e-6);
}

TEST(GravityManifold, RefusesAZeroVector) {
  const GravityManifold manifold;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const Eigen::Vector2d w(0.1, 0.2);
  Eigen::Vector3d out;
  EXPECT_FALSE(manifold.Plus(zero.data(), w.data(), out.data()));
  Eigen::Matrix<double, 3, 2> jacobian;
  EXPECT_FALSE(manifold.PlusJacobian(zero.data(), jacobian.data()));
}

}  // namespace
}  // namespace splinecal
