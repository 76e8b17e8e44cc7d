#include "splinecal/spline/segment.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <random>
#include <vector>

#include "spline/spline_test_util.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

using testing::RelativelyNear;

// The scaled exponential and lie/se3.h's Exp evaluate the same closed forms in a different
// order: agreement to a few ulps of O(1..10) entries.
constexpr double kSameFormulaTolerance = 1e-13;
// Series vs closed form on either side of the x = 0.1 switch: both exact to ~1e-14 relative
// (segment.h, kExpSeriesThresholdSq).
constexpr double kBranchTolerance = 1e-13;

// Rotation angles |b phi| that exercise every branch: zero, tiny, around the series switch
// (0.1 rad), generic, and near pi.
const std::vector<double>& TestAngles() {
  static const std::vector<double> angles = {
      0.0, 1e-9, 1e-4, 0.05, 0.0999999, 0.1000001, 0.3, 1.0, 2.5, kPi - 1e-6};
  return angles;
}

KnotDelta<double> DeltaOf(const Vector6d& omega) { return MakeKnotDelta(SE3d(), SE3d::Exp(omega)); }

TEST(ExpCoefficients, SeriesAndClosedFormsMeetAtThreshold) {
  const double x_sq = internal::kExpSeriesThresholdSq;
  const auto below = internal::ComputeExpCoefficients(x_sq * (1 - 1e-12), true);
  const auto above = internal::ComputeExpCoefficients(x_sq * (1 + 1e-12), true);
  EXPECT_NEAR(below.cos_half, above.cos_half, kBranchTolerance);
  EXPECT_NEAR(below.h, above.h, kBranchTolerance);
  EXPECT_NEAR(below.c1, above.c1, kBranchTolerance);
  EXPECT_NEAR(below.c2, above.c2, kBranchTolerance);
  EXPECT_NEAR(below.c3, above.c3, kBranchTolerance);
  EXPECT_NEAR(below.c4, above.c4, kBranchTolerance);
  // c5 loses ~120 eps / x^4 = 2.7e-10 relative to cancellation in the closed form.
  EXPECT_NEAR(below.c5, above.c5, 1e-11);
}

TEST(ExpCoefficients, MatchDefinitionsAtGenericAngle) {
  const double x = 0.7;
  const auto k = internal::ComputeExpCoefficients(x * x, true);
  EXPECT_NEAR(k.cos_half, std::cos(x / 2), 1e-15);
  EXPECT_NEAR(k.h, std::sin(x / 2) / x, 1e-15);
  EXPECT_NEAR(k.c1, std::sin(x) / x, 1e-15);
  EXPECT_NEAR(k.c2, (1 - std::cos(x)) / (x * x), 1e-15);
  EXPECT_NEAR(k.c3, (x - std::sin(x)) / (x * x * x), 1e-14);
  EXPECT_NEAR(k.c4, (x * x + 2 * std::cos(x) - 2) / (2 * std::pow(x, 4)), 1e-13);
  EXPECT_NEAR(k.c5, (2 * x - 3 * std::sin(x) + x * std::cos(x)) / (2 * std::pow(x, 5)), 1e-12);
}

TEST(ScaledExp, MatchesLieExpOfScaledTwist) {
  std::mt19937 rng(1);
  for (double angle : TestAngles()) {
    for (double b : {0.0, 1.0 / 6.0, 0.5, 5.0 / 6.0, 1.0}) {
      Vector6d omega;
      omega.head<3>() = Eigen::Vector3d(0.7, -1.3, 2.1);
      omega.tail<3>() = angle * testing::RandomUnitVector(&rng);
      const KnotDelta<double> delta = DeltaOf(omega);
      internal::ScaledExp<double> A;
      internal::ComputeScaledExp(delta, b, true, false, &A);
      const SE3d expected =
          SE3d::Exp(b * Vector6d((Vector6d() << delta.rho, delta.phi).finished()));
      EXPECT_TRUE(RelativelyNear(A.R, expected.rotationMatrix(), kSameFormulaTolerance))
          << angle << " " << b;
      EXPECT_TRUE(RelativelyNear(A.t, expected.translation(), kSameFormulaTolerance))
          << angle << " " << b;
      EXPECT_TRUE(
          RelativelyNear(A.q.coeffs(), expected.so3().quaternion().coeffs(), kSameFormulaTolerance))
          << angle << " " << b;
      EXPECT_TRUE(RelativelyNear(A.q.toRotationMatrix(), A.R, kSameFormulaTolerance));
    }
  }
}

// b Jr(b Omega) from the cached Q terms equals b times lie/se3.h's RightJacobianSE3.
TEST(ScaledRightJacobian, MatchesLieRightJacobianSE3) {
  std::mt19937 rng(2);
  for (double angle : TestAngles()) {
    for (double b : {0.0, 1.0 / 6.0, 0.5, 1.0}) {
      Vector6d omega;
      omega.head<3>() = Eigen::Vector3d(-0.4, 1.1, 0.9);
      omega.tail<3>() = angle * testing::RandomUnitVector(&rng);
      const KnotDelta<double> delta = DeltaOf(omega);
      const KnotDeltaJacobians cache = MakeKnotDeltaJacobians(delta);
      internal::ScaledExp<double> A;
      internal::ComputeScaledExp(delta, b, true, true, &A);
      Eigen::Matrix3d b_Jr;
      internal::ScaledRightJacobianSO3(delta, A, &b_Jr);
      const Eigen::Matrix3d b_Qr = b * internal::ScaledQRight(delta, cache, A);
      const Vector6d omega_cached = (Vector6d() << delta.rho, delta.phi).finished();
      const Matrix6d expected = b * RightJacobianSE3(Vector6d(b * omega_cached));
      EXPECT_TRUE(RelativelyNear(b_Jr, expected.topLeftCorner<3, 3>(), kSameFormulaTolerance))
          << angle << " " << b;
      EXPECT_TRUE(RelativelyNear(b_Qr, expected.topRightCorner<3, 3>(), 1e-12))
          << angle << " " << b;
    }
  }
}

TEST(KnotDeltaJacobians, MatchLieInverseJacobians) {
  std::mt19937 rng(3);
  for (double angle : TestAngles()) {
    Vector6d omega;
    omega.head<3>() = Eigen::Vector3d(1.5, 0.2, -0.8);
    omega.tail<3>() = angle * testing::RandomUnitVector(&rng);
    const KnotDelta<double> delta = DeltaOf(omega);
    const Vector6d omega_cached = (Vector6d() << delta.rho, delta.phi).finished();
    const KnotDeltaJacobians J = MakeKnotDeltaJacobians(delta);
    const Matrix6d Jr_inv = RightJacobianInverseSE3(omega_cached);
    const Matrix6d Jl_inv = LeftJacobianInverseSE3(omega_cached);
    // Near pi the inverse Jacobians grow like 1/(pi - angle); compare relatively.
    EXPECT_TRUE(RelativelyNear(J.Jr_inv_diag, Jr_inv.topLeftCorner<3, 3>(), 1e-12)) << angle;
    EXPECT_TRUE(RelativelyNear(J.Jr_inv_upper, Jr_inv.topRightCorner<3, 3>(), 1e-12)) << angle;
    EXPECT_TRUE(RelativelyNear(J.Jl_inv_diag, Jl_inv.topLeftCorner<3, 3>(), 1e-12)) << angle;
    EXPECT_TRUE(RelativelyNear(J.Jl_inv_upper, Jl_inv.topRightCorner<3, 3>(), 1e-12)) << angle;
    EXPECT_TRUE((Jr_inv.bottomLeftCorner<3, 3>().isZero()));
  }
}

TEST(MakeKnotDelta, CachesOmegaAndInvariants) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(2, 4);
  const KnotDelta<double> delta = MakeKnotDelta(poses[0], poses[1]);
  const Vector6d omega = (poses[0].inverse() * poses[1]).Log();
  EXPECT_EQ(delta.rho, omega.head<3>());
  EXPECT_EQ(delta.phi, omega.tail<3>());
  EXPECT_DOUBLE_EQ(delta.theta_sq, omega.tail<3>().squaredNorm());
  EXPECT_TRUE(RelativelyNear(delta.phi_x_rho, delta.phi.cross(delta.rho), 1e-16));
  EXPECT_TRUE(
      RelativelyNear(delta.phi_x_phi_x_rho, delta.phi.cross(delta.phi.cross(delta.rho)), 1e-16));
}

// A SegmentKnotData built from the four poses of a segment gives the spline's values and
// Jacobians: the same code path as a cost function that receives four pose blocks.
TEST(SegmentKnotData, MatchesSplineSegment) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(7, 5);
  const SE3Splined spline(poses, 0, 100000000);
  const Segment<double> segment = spline.SegmentAt(0.33);
  const int f = segment.first_index();
  const SegmentKnotData<double> data(poses[f], poses[f + 1], poses[f + 2], poses[f + 3], true, f);
  SE3d T_a, T_b;
  Eigen::Vector3d w_a, w_b, a_a, a_b;
  EvaluateSegment(data.knots(), segment, &T_a, &w_a, nullptr, nullptr, &a_a);
  spline.Evaluate(segment, &T_b, &w_b, nullptr, nullptr, &a_b);
  EXPECT_EQ(T_a.matrix(), T_b.matrix());
  EXPECT_EQ(w_a, w_b);
  EXPECT_EQ(a_a, a_b);
  ControlPoseJacobian<3> J_a, J_b;
  EvaluateLinearAccelerationJacobian(data.knots(), segment, nullptr, &J_a);
  spline.EvaluateLinearAccelerationJacobian(segment, nullptr, &J_b);
  EXPECT_EQ(J_a.first_index, J_b.first_index);
  for (int k = 0; k < 4; ++k) EXPECT_EQ(J_a.blocks[k], J_b.blocks[k]);
}

TEST(SegmentKnotData, CompilesAndEvaluatesWithJets) {
  using Jet = ceres::Jet<double, 6>;
  const std::vector<SE3d> poses = testing::RandomControlPoses(4, 6);
  const SegmentKnotData<Jet> data(
      poses[0].cast<Jet>(), poses[1].cast<Jet>(), poses[2].cast<Jet>(), poses[3].cast<Jet>());
  EXPECT_EQ(data.knots().jacobians, nullptr);
  const Segment<Jet> segment = MakeSegment(1, Jet(0.25), 0.1);
  SE3<Jet> T_w_s;
  Vector3<Jet> w_s, w_dot_s, v_w, a_w;
  EvaluateSegment(data.knots(), segment, &T_w_s, &w_s, &w_dot_s, &v_w, &a_w);
  const SE3Splined spline(poses, 0, 100000000);
  SE3d T_d;
  Eigen::Vector3d a_d;
  spline.Evaluate(MakeSegment(1, 0.25, 0.1), &T_d, nullptr, nullptr, nullptr, &a_d);
  for (int r = 0; r < 3; ++r) {
    EXPECT_NEAR(T_w_s.translation()[r].a, T_d.translation()[r], 1e-12);
    EXPECT_NEAR(a_w[r].a, a_d[r], 1e-10);
  }
}

TEST(MakeSegment, ScalesBasisDerivativesByDt) {
  const double dt = 0.05;
  const Segment<double> segment = MakeSegment(3, 0.6, dt);
  EXPECT_EQ(segment.index, 3);
  EXPECT_EQ(segment.first_index(), 2);
  EXPECT_TRUE(RelativelyNear(segment.b_dot, CumulativeBasis<1>(0.6) / dt, 1e-15));
  EXPECT_TRUE(RelativelyNear(segment.b_ddot, CumulativeBasis<2>(0.6) / (dt * dt), 1e-15));
}

}  // namespace
}  // namespace splinecal
