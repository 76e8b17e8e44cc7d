#include "splinecal/estimation/gravity_tangent.h"

#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

// Orthonormality is a few roundings: 4 eps.
constexpr double kOrthonormalTolerance = 1e-15;

std::vector<Eigen::Vector3d> Directions() {
  std::vector<Eigen::Vector3d> directions = {
      Eigen::Vector3d::UnitX(),
      -Eigen::Vector3d::UnitX(),
      Eigen::Vector3d::UnitY(),
      -Eigen::Vector3d::UnitY(),
      Eigen::Vector3d::UnitZ(),
      -Eigen::Vector3d::UnitZ(),
      // A hair off the axes, where a basis built from e_z alone loses its digits.
      Eigen::Vector3d(1e-12, -1e-12, -1.0),
      Eigen::Vector3d(0.0, 1e-9, 1.0),
      // Ties between axes.
      Eigen::Vector3d(1.0, 1.0, 1.0),
      Eigen::Vector3d(1.0, -1.0, 0.0)};
  std::mt19937 rng(42);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int i = 0; i < 1000; ++i) directions.emplace_back(normal(rng), normal(rng), normal(rng));
  return directions;
}

void ExpectOrthonormalBasisOf(const Eigen::Vector3d& g) {
  const Eigen::Matrix<double, 3, 2> B = GravityTangentBasis(g);
  const Eigen::Vector3d d = g.normalized();
  EXPECT_TRUE(B.allFinite()) << g.transpose();
  EXPECT_LT((B.transpose() * B - Eigen::Matrix2d::Identity()).cwiseAbs().maxCoeff(),
            kOrthonormalTolerance)
      << g.transpose();
  EXPECT_LT((B.transpose() * d).cwiseAbs().maxCoeff(), kOrthonormalTolerance) << g.transpose();
  // Right-handed: b1 x b2 = d.
  EXPECT_LT((B.col(0).cross(B.col(1)) - d).norm(), 2.0 * kOrthonormalTolerance) << g.transpose();
}

TEST(GravityTangentBasis, OrthonormalForAxesAndRandomDirections) {
  for (const Eigen::Vector3d& direction : Directions()) {
    for (double norm : {1e-8, 1.0, 9.81, 1e8}) ExpectOrthonormalBasisOf(norm * direction);
  }
}

// VINS-Mono's basis, b1 = normalize(e_z - d (d . e_z)) unless d == e_z exactly, is 0/0 for
// gravity along -z: the reason this header exists.
TEST(GravityTangentBasis, VinsMonoBasisFailsAlongMinusZ) {
  const Eigen::Vector3d d = -Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d tmp = Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d unnormalised = tmp - d * d.dot(tmp);
  EXPECT_EQ(unnormalised.norm(), 0.0);
  ExpectOrthonormalBasisOf(9.81 * d);
}

TEST(RetractGravity, KeepsTheNormAndMovesByTheAngleAlongBw) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const Eigen::Vector3d& direction : Directions()) {
    const Eigen::Vector3d g = 9.81 * direction.normalized();
    const Eigen::Matrix<double, 3, 2> B = GravityTangentBasis(g);
    for (double angle : {1e-9, 1e-5, 0.3, 2.0}) {
      const Eigen::Vector2d w = angle * Eigen::Vector2d(normal(rng), normal(rng)).normalized();
      const Eigen::Vector3d moved = RetractGravity(g, w);
      EXPECT_NEAR(moved.norm(), 9.81, 1e-14);
      // Angle between g and the result: |w| (great circle), in the plane of g and B w.
      const double between = std::atan2(g.cross(moved).norm(), g.dot(moved));
      EXPECT_NEAR(between, angle, 1e-15 + 1e-14 * angle);
      const Eigen::Vector3d normal_of_plane = g.cross(B * w).normalized();
      EXPECT_LT(std::abs(normal_of_plane.dot(moved)), 1e-13);
      EXPECT_GT((B * w).dot(moved), 0.0);
    }
  }
}

TEST(RetractGravity, ZeroStepIsTheIdentityAndTheDerivativeIsNormTimesBasis) {
  for (const Eigen::Vector3d& direction : Directions()) {
    const Eigen::Vector3d g = 9.81 * direction.normalized();
    EXPECT_LT((RetractGravity(g, Eigen::Vector2d::Zero()) - g).norm(), 1e-14);
    const Eigen::Matrix<double, 3, 2> J = testing::CentralDifferenceJacobian(
        [&](const Eigen::Vector2d& w) -> Eigen::Vector3d { return RetractGravity(g, w); },
        Eigen::Vector2d::Zero());
    EXPECT_LT((J - 9.81 * GravityTangentBasis(g)).norm(), 1e-8) << g.transpose();
  }
}

// The small-angle series and the closed form agree where they meet (t^2 = 1e-8).
TEST(RetractGravity, SeriesContinuousAtItsThreshold) {
  const Eigen::Vector3d g(0.3, -9.2, 3.1);
  const double threshold = std::sqrt(internal::kGravityRetractSmallAngleSq);
  const Eigen::Vector2d dir = Eigen::Vector2d(0.6, 0.8);
  const Eigen::Vector3d below = RetractGravity(g, (threshold * (1.0 - 1e-12)) * dir);
  const Eigen::Vector3d above = RetractGravity(g, (threshold * (1.0 + 1e-12)) * dir);
  EXPECT_LT((below - above).norm(), 1e-14);
}

}  // namespace
}  // namespace splinecal
