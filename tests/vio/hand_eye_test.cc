#include "splinecal/vio/hand_eye.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

namespace splinecal {
namespace {

using ::testing::HasSubstr;

// Noise-free pairs give X to rounding (the eigenvector of a 4x4 symmetric matrix).
constexpr double kNoiseFreeTolerance = 1e-12;  // [rad]

struct Pairs {
  std::vector<SO3d> camera;  // R_ck_ck1
  std::vector<SO3d> imu;     // R_sk_sk1
};

// Rs_k = X^T Rc_k X for relative rotations about the given axes with the given angles.
Pairs MakePairs(const SO3d& X,
                const std::vector<Eigen::Vector3d>& axes,
                const std::vector<double>& angles) {
  Pairs pairs;
  for (size_t k = 0; k < axes.size(); ++k) {
    const SO3d Rc = SO3d::Exp(angles[k] * axes[k].normalized());
    pairs.camera.push_back(Rc);
    pairs.imu.push_back(X.inverse() * Rc * X);
  }
  return pairs;
}

Pairs RandomPairs(const SO3d& X, int n, double max_angle, uint32_t seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.2 * max_angle, max_angle);
  std::vector<Eigen::Vector3d> axes;
  std::vector<double> angles;
  for (int k = 0; k < n; ++k) {
    axes.emplace_back(normal(rng), normal(rng), normal(rng));
    angles.push_back(uniform(rng));
  }
  return MakePairs(X, axes, angles);
}

double AngleBetween(const SO3d& a, const SO3d& b) { return (a.inverse() * b).Log().norm(); }

TEST(EstimateHandEyeRotation, RecoversTheRotationFromNoiseFreePairs) {
  for (uint32_t seed = 1; seed <= 20; ++seed) {
    const SO3d X = SO3d::Exp(Eigen::Vector3d(0.4 * seed, -1.1, 0.3 * seed - 2.0));
    const Pairs pairs = RandomPairs(X, 50, 0.2, seed);
    const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
    ASSERT_TRUE(result.ok) << result.message;
    EXPECT_TRUE(result.message.empty());
    EXPECT_LT(AngleBetween(result.R_cam_imu, X), kNoiseFreeTolerance) << seed;
    // The square root of an eigenvalue at rounding level (~1e-16): ~1e-8.
    EXPECT_LT(result.singular_values(3), 1e-7);
    EXPECT_GT(result.second_axis_ratio, 0.5);
  }
}

// q and -q are the same rotation: inputs on either sheet give the same answer.
TEST(EstimateHandEyeRotation, IndependentOfQuaternionSigns) {
  const SO3d X = SO3d::Exp(Eigen::Vector3d(2.0, -0.5, 1.0));
  Pairs pairs = RandomPairs(X, 30, 0.3, 5);
  for (size_t k = 0; k < pairs.camera.size(); k += 2) {
    const Eigen::Quaterniond q = pairs.camera[k].quaternion();
    pairs.camera[k] = SO3d(Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z()));
  }
  for (size_t k = 1; k < pairs.imu.size(); k += 3) {
    const Eigen::Quaterniond q = pairs.imu[k].quaternion();
    pairs.imu[k] = SO3d(Eigen::Quaterniond(-q.w(), -q.x(), -q.y(), -q.z()));
  }
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  ASSERT_TRUE(result.ok);
  EXPECT_LT(AngleBetween(result.R_cam_imu, X), kNoiseFreeTolerance);
}

TEST(EstimateHandEyeRotation, NoisyPairsGiveAnErrorAtTheNoiseLevel) {
  const SO3d X = SO3d::Exp(Eigen::Vector3d(-1.0, 0.7, 0.2));
  Pairs pairs = RandomPairs(X, 100, 0.2, 9);
  std::mt19937 rng(11);
  std::normal_distribution<double> normal(0.0, 1.0);
  constexpr double kNoise = 1e-3;  // [rad] per pair and axis
  for (SO3d& R : pairs.camera) {
    R = R * SO3d::Exp(kNoise * Eigen::Vector3d(normal(rng), normal(rng), normal(rng)));
  }
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  ASSERT_TRUE(result.ok);
  // Each pair constrains X to ~noise / angle (0.04..0.2 rad): 100 pairs give ~1e-3 rad.
  EXPECT_LT(AngleBetween(result.R_cam_imu, X), 3e-3);
}

TEST(EstimateHandEyeRotation, RefusesRotationAboutOneAxis) {
  const SO3d X = SO3d::Exp(Eigen::Vector3d(0.3, 0.2, -0.1));
  const Eigen::Vector3d axis(0.2, -0.3, 1.0);
  std::vector<Eigen::Vector3d> axes(40, axis);
  std::vector<double> angles;
  for (int k = 0; k < 40; ++k) angles.push_back(0.05 + 0.01 * (k % 7) - (k % 2 ? 0.2 : 0.0));
  const Pairs pairs = MakePairs(X, axes, angles);
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  EXPECT_FALSE(result.ok);
  EXPECT_THAT(result.message, HasSubstr("rotated about one axis only"));
  EXPECT_THAT(result.message, HasSubstr("--camchain"));
  EXPECT_LT(result.second_axis_ratio, 1e-6);
  // Two null directions: sigma_3 ~ sigma_4 ~ 0.
  EXPECT_LT(result.singular_values(2), 1e-6);
}

TEST(EstimateHandEyeRotation, RefusesTooLittleRotationAboutASecondAxis) {
  const SO3d X;
  // Mostly about z, with a weak second axis: ratio above 0.1 fails only the absolute bound.
  std::vector<Eigen::Vector3d> axes;
  std::vector<double> angles;
  for (int k = 0; k < 10; ++k) {
    axes.emplace_back(0.0, 0.0, 1.0);
    angles.push_back(0.02);
    axes.emplace_back(1.0, 0.0, 0.0);
    angles.push_back(0.005);
  }
  const Pairs pairs = MakePairs(X, axes, angles);
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  EXPECT_FALSE(result.ok);
  EXPECT_GT(result.second_axis_ratio, 0.1);
  EXPECT_LT(result.singular_values(2), 0.05);
  // The same motion with larger angles passes.
  for (double& angle : angles) angle *= 20.0;
  const Pairs larger = MakePairs(X, axes, angles);
  EXPECT_TRUE(EstimateHandEyeRotation(larger.camera, larger.imu).ok);
}

TEST(EstimateHandEyeRotation, RefusesFewerThanTwoPairs) {
  const Pairs pairs = RandomPairs(SO3d(), 1, 0.3, 1);
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  EXPECT_FALSE(result.ok);
  EXPECT_THAT(result.message, HasSubstr("fewer than 2 pairs"));
}

// sigma_3 / sigma_1 = sqrt((n2 + n3) / (n1 + n2)) for the axis matrix
// N = sum sin^2(t/2) a a^T (vio/hand_eye.h).
TEST(EstimateHandEyeRotation, SecondAxisRatioMatchesTheClosedForm) {
  const SO3d X = SO3d::Exp(Eigen::Vector3d(0.1, 0.9, -0.4));
  const std::vector<Eigen::Vector3d> axes = {
      Eigen::Vector3d::UnitX(), Eigen::Vector3d::UnitY(), Eigen::Vector3d::UnitZ()};
  const std::vector<double> angles = {0.3, 0.2, 0.1};
  const Pairs pairs = MakePairs(X, axes, angles);
  const HandEyeRotationResult result = EstimateHandEyeRotation(pairs.camera, pairs.imu);
  const double n1 = std::pow(std::sin(0.15), 2), n2 = std::pow(std::sin(0.1), 2),
               n3 = std::pow(std::sin(0.05), 2);
  EXPECT_NEAR(result.second_axis_ratio, std::sqrt((n2 + n3) / (n1 + n2)), 1e-12);
  EXPECT_NEAR(result.singular_values(0), 2.0 * std::sqrt(n1 + n2), 1e-12);
  EXPECT_NEAR(result.singular_values(1), 2.0 * std::sqrt(n1 + n3), 1e-12);
  EXPECT_NEAR(result.singular_values(2), 2.0 * std::sqrt(n2 + n3), 1e-12);
}

}  // namespace
}  // namespace splinecal
