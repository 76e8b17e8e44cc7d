// Test helpers for the spline and IMU-model tests: seeded generic control poses and relative
// comparisons. Header-only, test-only.
#ifndef SPLINECAL_TESTS_SPLINE_SPLINE_TEST_UTIL_H_
#define SPLINECAL_TESTS_SPLINE_SPLINE_TEST_UTIL_H_

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/types.h"

namespace splinecal {
namespace testing {

// A EuRoC-like t0 (V1_01_easy starts near 1.4037e18 ns): doubles cannot hold it to the ns.
inline constexpr int64_t kEurocLikeT0Ns = 1403715273262142976;
// 0.2 s between knots.
inline constexpr int64_t kTestDtNs = 200000000;

// A random unit vector.
inline Eigen::Vector3d RandomUnitVector(std::mt19937* rng) {
  std::normal_distribution<double> normal(0.0, 1.0);
  Eigen::Vector3d v(normal(*rng), normal(*rng), normal(*rng));
  return v.normalized();
}

// A random twist [rho; phi] with |phi| uniform in [min_angle, max_angle] rad and each component
// of rho uniform in [-max_translation, max_translation] m.
inline Vector6d RandomTwist(std::mt19937* rng,
                            double min_angle,
                            double max_angle,
                            double max_translation) {
  std::uniform_real_distribution<double> angle(min_angle, max_angle);
  std::uniform_real_distribution<double> offset(-max_translation, max_translation);
  Vector6d xi;
  xi.head<3>() = Eigen::Vector3d(offset(*rng), offset(*rng), offset(*rng));
  xi.tail<3>() = angle(*rng) * RandomUnitVector(rng);
  return xi;
}

// n control poses, generic (not near identity): a random first pose, then steps with rotations
// of min_angle..max_angle rad and translations up to max_translation m per axis.
inline std::vector<SE3d> RandomControlPoses(int n,
                                            uint32_t seed,
                                            double min_angle = 0.1,
                                            double max_angle = 1.0,
                                            double max_translation = 1.0) {
  std::mt19937 rng(seed);
  std::vector<SE3d> poses;
  poses.push_back(SE3d::Exp(RandomTwist(&rng, 0.5, 2.5, 3.0)));
  for (int i = 1; i < n; ++i) {
    poses.push_back(poses.back() *
                    SE3d::Exp(RandomTwist(&rng, min_angle, max_angle, max_translation)));
  }
  return poses;
}

// |a - b|_inf <= tolerance * max(1, |b|_inf): a relative check that does not divide by ~0.
template <typename A, typename B>
::testing::AssertionResult RelativelyNear(const A& a, const B& b, double tolerance) {
  const Eigen::MatrixXd ad = a;
  const Eigen::MatrixXd bd = b;
  if (ad.rows() != bd.rows() || ad.cols() != bd.cols()) {
    return ::testing::AssertionFailure() << "size mismatch";
  }
  const double scale = std::max(1.0, bd.lpNorm<Eigen::Infinity>());
  const double error = (ad - bd).lpNorm<Eigen::Infinity>();
  if (error <= tolerance * scale) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure()
         << "max abs difference " << error << " > " << tolerance << " * " << scale << "\nactual:\n"
         << ad << "\nexpected:\n"
         << bd;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_SPLINE_SPLINE_TEST_UTIL_H_
