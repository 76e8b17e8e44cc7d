// Tests of lie/se3_manifold.h: Ceres' manifold invariants (Plus/Minus identities and both
// Jacobians against Ridders numeric differentiation, EXPECT_THAT_MANIFOLD_INVARIANTS_HOLD) for
// SE3Manifold and SO3Manifold at random points with small and large deltas and at edge rotations;
// that Plus is the RIGHT perturbation T * Exp(d); the block layout; and that an autodiff
// derivative through PoseFromBlock times PlusJacobian is the right-perturbation Jacobian.
#include "splinecal/lie/se3_manifold.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "splinecal/units.h"
#include "testing/manifold_invariants.h"
#include "testing/numeric_diff.h"
#include "testing/rotations.h"

namespace splinecal {
namespace {

using testing::RandomQuaternion;

using ceres::Matrix;
using ceres::Vector;
using testing::ExpectManifoldInvariantsHold;

// Ceres' invariant checks compare relative norms; the Jacobian checks use Ridders' method (its
// error ~1e-11 on these smooth maps). Ceres' own manifold tests use 1e-9 for rotations.
constexpr double kManifoldTolerance = 1e-9;
// Plus/Minus against the group operations: a few dozen flops, translations up to ~10.
constexpr double kExactTolerance = 1e-12;
constexpr int kNumTrials = 200;

SE3d RandomPose(std::mt19937* rng) {
  std::normal_distribution<double> normal;
  return SE3d(SO3d(RandomQuaternion(rng)),
              Eigen::Vector3d(3.0 * normal(*rng), 3.0 * normal(*rng), 3.0 * normal(*rng)));
}

Vector PoseVector(const SE3d& pose) {
  Vector block(kPoseBlockSize);
  PoseToBlock(pose, block.data());
  return block;
}

// Plus(x, Minus(y, x)) reproduces y only up to the sign of its quaternion (Minus takes the
// shortest rotation), while Ceres compares the ambient vectors: put y's quaternion in x's
// hemisphere.
void MatchHemisphere(const Vector& x, int quaternion_offset, Vector* y) {
  if (x.segment<4>(quaternion_offset).dot(y->segment<4>(quaternion_offset)) < 0.0) {
    y->segment<4>(quaternion_offset) *= -1.0;
  }
}

// A tangent [rho; phi] with |phi| = angle (random axis) and rho with N(0, scale^2) entries.
Vector RandomDelta(double angle, double scale, std::mt19937* rng) {
  std::normal_distribution<double> normal;
  const Eigen::Vector3d axis =
      Eigen::Vector3d(normal(*rng), normal(*rng), normal(*rng)).normalized();
  Vector delta(6);
  delta << scale * normal(*rng), scale * normal(*rng), scale * normal(*rng), angle * axis;
  return delta;
}

TEST(SE3Manifold, InvariantsHoldAtRandomPoints) {
  const SE3Manifold manifold;
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> angle(0.0, kPi - 1e-3);
  for (int trial = 0; trial < kNumTrials; ++trial) {
    const Vector x = PoseVector(RandomPose(&rng));
    Vector y = PoseVector(RandomPose(&rng));
    MatchHemisphere(x, 3, &y);
    // Deltas from small to large (rotation up to pi - 1e-3: Minus(Plus(x, d), x) = d needs
    // |phi| < pi; translation up to ~10 m). Not smaller than 1e-4: Ceres checks
    // Minus(Plus(x, d), x) = d RELATIVE to |d|, and the translation goes through t + R rho, which
    // loses eps |t| ~ 1e-15 absolutely (|t| ~ 5 m); below |d| ~ 1e-6 no implementation passes.
    const double scale = (trial % 3 == 0) ? 1e-4 : ((trial % 3 == 1) ? 0.1 : 5.0);
    const Vector delta = RandomDelta(trial % 3 == 0 ? 1e-4 : angle(rng), scale, &rng);
    ExpectManifoldInvariantsHold(manifold, x, delta, y, kManifoldTolerance);
  }
}

TEST(SE3Manifold, InvariantsHoldAtEdgeRotations) {
  const SE3Manifold manifold;
  std::mt19937 rng(22);
  const Eigen::Vector3d axis = Eigen::Vector3d(0.2, -0.7, 0.4).normalized();
  const Eigen::Vector3d t(1.0, -2.0, 0.5);
  // Identity, tiny, generic, and just below pi (w = cos(angle/2) ~ 5e-7).
  for (const double x_angle : {0.0, 1e-9, 0.3, kPi - 1e-6}) {
    const Vector x = PoseVector(SE3d(SO3d::Exp(x_angle * axis), t));
    for (const double delta_angle : {0.0, 1e-9, 0.3, 3.0, kPi - 1e-3}) {
      Vector y = PoseVector(RandomPose(&rng));
      MatchHemisphere(x, 3, &y);
      const Vector delta = RandomDelta(delta_angle, 1.0, &rng);
      ExpectManifoldInvariantsHold(manifold, x, delta, y, kManifoldTolerance);
    }
  }
}

TEST(SE3Manifold, PlusIsRightMultiplicationByExp) {
  const SE3Manifold manifold;
  std::mt19937 rng(23);
  for (int trial = 0; trial < 100; ++trial) {
    const SE3d pose = RandomPose(&rng);
    const Vector delta = RandomDelta(2.0, 1.0, &rng);
    const Vector x = PoseVector(pose);
    Vector x_plus_delta(kPoseBlockSize);
    ASSERT_TRUE(manifold.Plus(x.data(), delta.data(), x_plus_delta.data()));
    const SE3d expected = pose * SE3d::Exp(Vector6d(delta));
    EXPECT_LT((PoseFromBlock(x_plus_delta.data()).matrix() - expected.matrix()).norm(),
              kExactTolerance);
    Vector y_minus_x(6);
    ASSERT_TRUE(manifold.Minus(x_plus_delta.data(), x.data(), y_minus_x.data()));
    EXPECT_LT((y_minus_x - delta).norm(), kExactTolerance);
  }
}

TEST(SE3Manifold, BlockLayoutIsTranslationThenEigenQuaternion) {
  const Eigen::Quaterniond q = Eigen::Quaterniond(0.5, 0.1, -0.3, 0.7).normalized();
  const SE3d pose(SO3d(q), Eigen::Vector3d(1.0, 2.0, 3.0));
  double block[kPoseBlockSize];
  PoseToBlock(pose, block);
  const double expected[kPoseBlockSize] = {1.0, 2.0, 3.0, q.x(), q.y(), q.z(), q.w()};
  for (int i = 0; i < kPoseBlockSize; ++i) EXPECT_EQ(block[i], expected[i]) << i;

  // PoseFromBlock normalises the quaternion it reads.
  double scaled[kPoseBlockSize] = {1.0, 2.0, 3.0, 2 * q.x(), 2 * q.y(), 2 * q.z(), 2 * q.w()};
  EXPECT_LT((PoseFromBlock(scaled).matrix() - pose.matrix()).norm(), kExactTolerance);
}

TEST(SE3Manifold, AutodiffThroughBlockTimesPlusJacobianIsRightPerturbationJacobian) {
  // A cost-function developer writes f(block) with Jets; Ceres multiplies d f / d block by
  // PlusJacobian. The product must be d f(T Exp(d)) / d d (here f = T^-1 p, a point expressed
  // in the pose's frame).
  using Jet7 = ceres::Jet<double, 7>;
  const SE3Manifold manifold;
  std::mt19937 rng(24);
  const Eigen::Vector3d p_w(4.0, -1.0, 2.5);
  for (int trial = 0; trial < 20; ++trial) {
    const SE3d T_w_s = RandomPose(&rng);
    const Vector x = PoseVector(T_w_s);
    Jet7 block[kPoseBlockSize];
    for (int i = 0; i < kPoseBlockSize; ++i) block[i] = Jet7(x(i), i);
    const Vector3<Jet7> p_s = PoseFromBlock(block).inverse() * p_w.cast<Jet7>();
    Eigen::Matrix<double, 3, 7> J_p_block;
    for (int r = 0; r < 3; ++r) J_p_block.row(r) = p_s(r).v.transpose();
    Eigen::Matrix<double, 7, 6, Eigen::RowMajor> plus_jacobian;
    ASSERT_TRUE(manifold.PlusJacobian(x.data(), plus_jacobian.data()));

    const Eigen::MatrixXd numeric = testing::RightPerturbationJacobian(
        [&](const SE3d& pose) -> Eigen::Vector3d { return pose.inverse() * p_w; }, T_w_s);
    // Analytic: d (Exp(-d) T^-1 p) / d d = [-I, Hat(T^-1 p)].
    Eigen::Matrix<double, 3, 6> analytic;
    analytic << -Eigen::Matrix3d::Identity(), Hat(T_w_s.inverse() * p_w);
    EXPECT_LT((J_p_block * plus_jacobian - analytic).norm(), kExactTolerance);
    EXPECT_LT((numeric - analytic).norm(), 1e-8);  // Central differences, step 1e-5.
  }
}

TEST(SO3Manifold, InvariantsHoldAtRandomAndEdgePoints) {
  const SO3Manifold manifold;
  std::mt19937 rng(25);
  std::uniform_real_distribution<double> angle(0.0, kPi - 1e-3);
  std::vector<Eigen::Quaterniond> points = {
      Eigen::Quaterniond::Identity(), Eigen::Quaterniond(1e-12, std::sqrt(1.0 - 1e-24), 0.0, 0.0)};
  for (int trial = 0; trial < kNumTrials; ++trial) points.push_back(RandomQuaternion(&rng));
  for (const Eigen::Quaterniond& q : points) {
    Vector x(4);
    RotationToBlock(SO3d(q), x.data());
    Vector y(4);
    RotationToBlock(SO3d(RandomQuaternion(&rng)), y.data());
    MatchHemisphere(x, 0, &y);
    const Vector delta = RandomDelta(angle(rng), 0.0, &rng).tail<3>();
    ExpectManifoldInvariantsHold(manifold, x, delta, y, kManifoldTolerance);
  }
}

TEST(SO3Manifold, PlusIsRightMultiplicationByExp) {
  const SO3Manifold manifold;
  const SO3d r = SO3d::Exp(Eigen::Vector3d(0.3, -1.0, 2.0));
  const Eigen::Vector3d delta(-0.5, 0.2, 1.5);
  double x[kRotationBlockSize];
  double x_plus_delta[kRotationBlockSize];
  RotationToBlock(r, x);
  ASSERT_TRUE(manifold.Plus(x, delta.data(), x_plus_delta));
  EXPECT_LT(((RotationFromBlock(x_plus_delta).inverse() * r * SO3d::Exp(delta)).Log()).norm(),
            kExactTolerance);
}

}  // namespace
}  // namespace splinecal
