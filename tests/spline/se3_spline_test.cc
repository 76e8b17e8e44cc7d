#include "splinecal/spline/se3_spline.h"

#include <ceres/jet.h>
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <initializer_list>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "spline/spline_checks.h"
#include "spline/spline_test_util.h"
#include "splinecal/error.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/segment_jacobians.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

using testing::EvaluateAll;
using testing::EvaluateAt;
using testing::InteriorTimes;
using testing::RelativelyNear;

// Jacobians vs central differences in the right perturbation (h = 1e-5): errors ~1e-10 on
// O(1..100) entries; 1e-6 relative leaves margin yet catches any wrong term (O(1) relative).
constexpr double kJacobianTolerance = 1e-6;
// Identities that hold exactly up to rounding of a few dozen operations on O(10) values.
constexpr double kRoundingTolerance = 1e-11;

constexpr int kNumPoses = testing::kRandomSplinePoses;

SE3Splined MakeRandomSpline(uint32_t seed, double min_angle = 0.1, double max_angle = 1.0) {
  return testing::RandomSpline(seed, TrajectoryModel::kSE3, min_angle, max_angle);
}

// Relative times [s] spread over every segment, including knots and both ends.
std::vector<double> SampleTimes(const SE3Splined& spline) {
  std::vector<double> times;
  const double t_begin = spline.start_time();
  const double t_end = spline.end_time();
  for (int k = 0; k <= 20; ++k) times.push_back(t_begin + (t_end - t_begin) * k / 20.0);
  times.push_back(t_begin + 0.37 * spline.dt());
  return times;
}

using State = testing::SplineState;

// ---------------------------------------------------------------------------------------------
// Construction and time handling.

TEST(SE3Spline, RejectsFewerThanFourControlPoses) {
  const std::vector<SE3d> poses(3);
  EXPECT_THROW(SE3Splined(poses, 0, 1000), Error);
  try {
    SE3Splined spline(poses, 0, 1000);
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("at least 4 control poses"));
  }
}

TEST(SE3Spline, RejectsNonPositiveDt) {
  const std::vector<SE3d> poses(5);
  EXPECT_THROW(SE3Splined(poses, 0, 0), Error);
  EXPECT_THROW(SE3Splined(poses, 0, -5), Error);
}

TEST(SE3Spline, RejectsKnotTimesOverflowingInt64) {
  const std::vector<SE3d> poses(5);
  EXPECT_THROW(SE3Splined(poses, std::numeric_limits<int64_t>::max() - 10, 1000), Error);
}

TEST(SE3Spline, ExposesWhatAWriterNeeds) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(6, 3);
  const SE3Splined spline(poses, testing::kEurocLikeT0Ns, testing::kTestDtNs);
  EXPECT_EQ(spline.num_control_poses(), 6);
  EXPECT_EQ(spline.num_segments(), 3);
  EXPECT_EQ(spline.t0_ns(), testing::kEurocLikeT0Ns);
  EXPECT_EQ(spline.dt_ns(), testing::kTestDtNs);
  EXPECT_DOUBLE_EQ(spline.dt(), 0.2);
  EXPECT_EQ(spline.knot_time_ns(3), testing::kEurocLikeT0Ns + 3 * testing::kTestDtNs);
  EXPECT_EQ(spline.start_time_ns(), spline.knot_time_ns(1));
  EXPECT_EQ(spline.end_time_ns(), spline.knot_time_ns(4));
  ASSERT_EQ(spline.control_poses().size(), 6u);
  EXPECT_EQ(spline.control_poses()[2].translation(), poses[2].translation());
}

TEST(SE3Spline, OutOfRangeTimeThrows) {
  const SE3Splined spline = MakeRandomSpline(1);
  EXPECT_THROW(spline.SegmentAtNs(spline.start_time_ns() - 1), Error);
  EXPECT_THROW(spline.SegmentAtNs(spline.end_time_ns() + 1), Error);
  EXPECT_THROW(spline.SegmentAtNs(spline.t0_ns()), Error);
  EXPECT_THROW(spline.SegmentAt(spline.start_time() - 1e-6), Error);
  EXPECT_THROW(spline.SegmentAt(spline.end_time() + 1e-6), Error);
  EXPECT_THROW(spline.SegmentAt(-1.0), Error);
  EXPECT_THROW(spline.SegmentAt(std::numeric_limits<double>::quiet_NaN()), Error);
  EXPECT_THROW(spline.SegmentAt(std::numeric_limits<double>::infinity()), Error);
  EXPECT_THROW(spline.PoseNs(spline.end_time_ns() + 1), Error);
  try {
    spline.SegmentAtNs(spline.end_time_ns() + 1);
    FAIL() << "no throw";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("outside the valid range"));
  }
}

TEST(SE3Spline, EndTimeEvaluatesLastSegmentAtUOne) {
  const SE3Splined spline = MakeRandomSpline(2);
  const Segment<double> by_ns = spline.SegmentAtNs(spline.end_time_ns());
  EXPECT_EQ(by_ns.index, spline.num_control_poses() - 3);
  EXPECT_EQ(by_ns.u, 1.0);
  const Segment<double> by_s = spline.SegmentAt(spline.end_time());
  EXPECT_EQ(by_s.index, spline.num_control_poses() - 3);
  EXPECT_NEAR(by_s.u, 1.0, 1e-12);
  // The end equals the limit from inside.
  const State end = EvaluateAll(spline, by_ns);
  const State inside = EvaluateAt(spline, spline.end_time() - 1e-9);
  EXPECT_TRUE(RelativelyNear(end.T_w_s.translation(), inside.T_w_s.translation(), 1e-7));
  EXPECT_TRUE(RelativelyNear(end.v_w, inside.v_w, 1e-6));
  // The start evaluates too (segment 1, u = 0).
  const Segment<double> start = spline.SegmentAtNs(spline.start_time_ns());
  EXPECT_EQ(start.index, 1);
  EXPECT_EQ(start.u, 0.0);
}

TEST(SE3Spline, NanosecondLookupIsExactNearEurocTimestamps) {
  const SE3Splined spline = MakeRandomSpline(3);
  // t = t_2 + dt / 4 exactly: a double holding 1.4e18 ns would be off by up to 128 ns.
  const Segment<double> segment = spline.SegmentAtNs(spline.knot_time_ns(2) + spline.dt_ns() / 4);
  EXPECT_EQ(segment.index, 2);
  EXPECT_EQ(segment.u, 0.25);
  const Segment<double> at_knot = spline.SegmentAtNs(spline.knot_time_ns(3));
  EXPECT_EQ(at_knot.index, 3);
  EXPECT_EQ(at_knot.u, 0.0);
  // The relative-seconds path agrees.
  const double t_s = spline.TimeSinceT0(spline.knot_time_ns(2) + spline.dt_ns() / 4);
  EXPECT_EQ(spline.SegmentAt(t_s).index, 2);
  EXPECT_NEAR(spline.SegmentAt(t_s).u, 0.25, 1e-14);
}

TEST(SE3Spline, SegmentCarriesTimeDerivativesOfBasis) {
  const SE3Splined spline = MakeRandomSpline(4);
  const Segment<double> segment = spline.SegmentAt(spline.start_time() + 1.3 * spline.dt());
  const double dt = spline.dt();
  EXPECT_EQ(segment.index, 2);
  EXPECT_TRUE(RelativelyNear(segment.b, CumulativeBasis<0>(segment.u), 1e-15));
  EXPECT_TRUE(RelativelyNear(segment.b_dot, CumulativeBasis<1>(segment.u) / dt, 1e-15));
  EXPECT_TRUE(RelativelyNear(segment.b_ddot, CumulativeBasis<2>(segment.u) / (dt * dt), 1e-15));
}

// ---------------------------------------------------------------------------------------------
// Values.

TEST(SE3Spline, PoseMatchesDefinitionWithLieExp) {
  const SE3Splined spline = MakeRandomSpline(5);
  const auto& P = spline.control_poses();
  for (double t : SampleTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    const int i = seg.index;
    SE3d expected = P[i - 1];
    for (int j = 1; j <= 3; ++j) {
      const Vector6d omega = (P[i + j - 2].inverse() * P[i + j - 1]).Log();
      expected = expected * SE3d::Exp(seg.b[j] * omega);
    }
    const SE3d actual = spline.Pose(t);
    EXPECT_TRUE(RelativelyNear(actual.matrix(), expected.matrix(), kRoundingTolerance)) << t;
  }
}

TEST(SE3Spline, OptionalOutputsAgreeWithFullEvaluation) {
  const SE3Splined spline = MakeRandomSpline(6);
  const Segment<double> seg = spline.SegmentAt(spline.start_time() + 2.6 * spline.dt());
  const State all = EvaluateAll(spline, seg);
  Eigen::Vector3d w_s, a_w, v_w, w_dot_s;
  spline.Evaluate(seg, nullptr, &w_s);
  EXPECT_EQ(w_s, all.w_s);
  spline.Evaluate(seg, nullptr, nullptr, nullptr, nullptr, &a_w);
  EXPECT_TRUE(RelativelyNear(a_w, all.a_w, 1e-15));
  spline.Evaluate(seg, nullptr, nullptr, nullptr, &v_w);
  EXPECT_TRUE(RelativelyNear(v_w, all.v_w, 1e-15));
  spline.Evaluate(seg, nullptr, nullptr, &w_dot_s);
  EXPECT_TRUE(RelativelyNear(w_dot_s, all.w_dot_s, 1e-15));
  SE3d T_w_s;
  spline.Evaluate(seg, &T_w_s);
  EXPECT_EQ(T_w_s.matrix(), all.T_w_s.matrix());
}

TEST(SE3Spline, TimeDerivativesMatchCentralDifferences) {
  for (uint32_t seed : {11u, 12u, 13u}) {
    testing::ExpectTimeDerivativesMatchCentralDifferences(MakeRandomSpline(seed));
  }
}

TEST(SE3Spline, WorldLinearAccelerationIsTheSecondDifferenceOfThePosition) {
  for (uint32_t seed : {11u, 12u, 13u}) {
    const SE3Splined spline = MakeRandomSpline(seed);
    for (double t : InteriorTimes(spline)) {
      const State s = EvaluateAt(spline, t);
      const double h = 1e-4;  // second difference: rounding eps |p| / h^2 ~ 1e-7 m/s^2
      const Eigen::Vector3d a_from_p =
          (spline.Pose(t + h).translation() - 2.0 * s.T_w_s.translation() +
           spline.Pose(t - h).translation()) /
          (h * h);
      EXPECT_TRUE(RelativelyNear(s.a_w, a_from_p, 1e-5)) << t;
    }
  }
}

TEST(SE3Spline, IsC2ContinuousAcrossKnots) {
  const SE3Splined spline = MakeRandomSpline(21);
  for (int k = 2; k <= spline.num_control_poses() - 3; ++k) {
    // Knot t_k: end of segment k-1 (u = 1) and start of segment k (u = 0).
    const State left = EvaluateAll(spline, MakeSegment(k - 1, 1.0, spline.dt()));
    const State right = EvaluateAll(spline, MakeSegment(k, 0.0, spline.dt()));
    EXPECT_TRUE(RelativelyNear(left.T_w_s.matrix(), right.T_w_s.matrix(), kRoundingTolerance));
    EXPECT_TRUE(RelativelyNear(left.w_s, right.w_s, kRoundingTolerance)) << k;
    EXPECT_TRUE(RelativelyNear(left.w_dot_s, right.w_dot_s, kRoundingTolerance)) << k;
    EXPECT_TRUE(RelativelyNear(left.v_w, right.v_w, kRoundingTolerance)) << k;
    EXPECT_TRUE(RelativelyNear(left.a_w, right.a_w, kRoundingTolerance)) << k;
  }
}

TEST(SE3Spline, EqualControlPosesGiveZeroRates) {
  std::mt19937 rng(7);
  const SE3d pose = SE3d::Exp(testing::RandomTwist(&rng, 0.5, 2.0, 3.0));
  const SE3Splined spline(std::vector<SE3d>(6, pose), 0, 50000000);
  for (double t : SampleTimes(spline)) {
    const State s = EvaluateAt(spline, t);
    EXPECT_TRUE(RelativelyNear(s.T_w_s.matrix(), pose.matrix(), 1e-14)) << t;
    EXPECT_LT(s.w_s.norm(), 1e-15);
    EXPECT_LT(s.w_dot_s.norm(), 1e-15);
    EXPECT_LT(s.v_w.norm(), 1e-15);
    EXPECT_LT(s.a_w.norm(), 1e-15);
  }
}

// Control poses on a one-parameter subgroup, T_i = Exp(i dt xi): T(t) = Exp((t - t0) xi) (the
// cumulative weights sum to 1 + u), so the body twist is xi everywhere: w_s = omega,
// R^T v_w = v, zero angular acceleration, and a_w = R (omega x v).
TEST(SE3Spline, OneParameterSubgroupHasConstantBodyTwist) {
  std::mt19937 rng(8);
  for (int trial = 0; trial < 5; ++trial) {
    const Vector6d xi = testing::RandomTwist(&rng, 0.5, 3.0, 2.0);  // [m/s; rad/s]
    const int64_t dt_ns = 100000000;
    const double dt = 0.1;
    std::vector<SE3d> poses;
    for (int i = 0; i < 7; ++i) poses.push_back(SE3d::Exp((i * dt) * xi));
    const SE3Splined spline(poses, testing::kEurocLikeT0Ns, dt_ns);
    for (double t : SampleTimes(spline)) {
      const State s = EvaluateAt(spline, t);
      const Eigen::Matrix3d R = s.T_w_s.rotationMatrix();
      EXPECT_TRUE(RelativelyNear(s.T_w_s.matrix(), SE3d::Exp(t * xi).matrix(), kRoundingTolerance));
      EXPECT_TRUE(RelativelyNear(s.w_s, xi.tail<3>(), kRoundingTolerance)) << t;
      EXPECT_TRUE(RelativelyNear(R.transpose() * s.v_w, xi.head<3>(), kRoundingTolerance)) << t;
      EXPECT_LT(s.w_dot_s.norm(), 1e-10) << t;
      EXPECT_TRUE(RelativelyNear(s.a_w, R * xi.tail<3>().cross(xi.head<3>()), kRoundingTolerance))
          << t;
    }
  }
}

// With equal rotations, Omega_k = [R^T (p_k - p_{k-1}); 0] and the SE(3) spline's translation is
// the ordinary cubic B-spline of the positions: p(u) = sum_m B_m(u) p_{i-1+m}.
TEST(SE3Spline, PureTranslationIsScalarCubicBSpline) {
  std::mt19937 rng(9);
  const SO3d R = SO3d::Exp(Eigen::Vector3d(0.3, -1.2, 0.5));
  std::uniform_real_distribution<double> position(-5.0, 5.0);
  std::vector<SE3d> poses;
  for (int i = 0; i < 7; ++i) {
    poses.emplace_back(R, Eigen::Vector3d(position(rng), position(rng), position(rng)));
  }
  const SE3Splined spline(poses, 1000, 250000000);
  const double dt = spline.dt();
  for (double t : SampleTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    const double u = seg.u;
    // Standard (non-cumulative) uniform cubic basis and its u-derivatives.
    const Eigen::Vector4d B((1 - u) * (1 - u) * (1 - u) / 6,
                            (3 * u * u * u - 6 * u * u + 4) / 6,
                            (-3 * u * u * u + 3 * u * u + 3 * u + 1) / 6,
                            u * u * u / 6);
    const Eigen::Vector4d dB(
        -(1 - u) * (1 - u) / 2, (9 * u * u - 12 * u) / 6, (-9 * u * u + 6 * u + 3) / 6, u * u / 2);
    const Eigen::Vector4d ddB(1 - u, (18 * u - 12) / 6, (-18 * u + 6) / 6, u);
    Eigen::Vector3d p = Eigen::Vector3d::Zero(), v = p, a = p;
    for (int m = 0; m < 4; ++m) {
      const Eigen::Vector3d& p_m = poses[seg.index - 1 + m].translation();
      p += B[m] * p_m;
      v += dB[m] / dt * p_m;
      a += ddB[m] / (dt * dt) * p_m;
    }
    const State s = EvaluateAll(spline, seg);
    EXPECT_TRUE(RelativelyNear(s.T_w_s.translation(), p, kRoundingTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.v_w, v, kRoundingTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.a_w, a, kRoundingTolerance)) << t;
    EXPECT_TRUE(RelativelyNear(s.T_w_s.rotationMatrix(), R.matrix(), 1e-15));
    EXPECT_LT(s.w_s.norm(), 1e-15);
  }
}

TEST(SE3Spline, SetControlPoseRefreshesCaches) {
  SE3Splined spline = MakeRandomSpline(31);
  const std::vector<SE3d> other = testing::RandomControlPoses(kNumPoses, 32);
  for (int i = 0; i < kNumPoses; ++i) spline.SetControlPose(i, other[i]);
  const SE3Splined fresh(other, spline.t0_ns(), spline.dt_ns());
  for (double t : SampleTimes(spline)) {
    const State a = EvaluateAt(spline, t);
    const State b = EvaluateAt(fresh, t);
    EXPECT_EQ(a.T_w_s.matrix(), b.T_w_s.matrix());
    EXPECT_EQ(a.a_w, b.a_w);
  }
  EXPECT_THROW(spline.SetControlPose(kNumPoses, SE3d()), Error);
  EXPECT_THROW(spline.SetControlPoses(std::vector<SE3d>(3)), Error);
}

TEST(SE3Spline, LargeRotationsBetweenControlPoses) {
  // Steps of 2.5-3.0 rad (Log stays below pi): values still match the definition and the rates
  // the central differences.
  const SE3Splined spline(testing::RandomControlPoses(kNumPoses, 41, 2.5, 3.0),
                          testing::kEurocLikeT0Ns,
                          testing::kTestDtNs);
  testing::ExpectTimeDerivativesMatchCentralDifferences(spline);
}

// ---------------------------------------------------------------------------------------------
// Jacobians with respect to control poses (right perturbation).

class SE3SplineJacobian : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(SE3SplineJacobian, PoseMatchesNumericRightPerturbation) {
  testing::ExpectPoseJacobianMatchesNumeric(
      TrajectoryModel::kSE3, GetParam(), {51u, 52u}, kRoundingTolerance, kJacobianTolerance);
}

TEST_P(SE3SplineJacobian, AngularVelocityMatchesNumericRightPerturbation) {
  testing::ExpectRateJacobianMatchesNumeric(testing::kAngularVelocity,
                                            TrajectoryModel::kSE3,
                                            GetParam(),
                                            {53u, 54u},
                                            1e-15,
                                            kJacobianTolerance);
}

TEST_P(SE3SplineJacobian, LinearAccelerationMatchesNumericRightPerturbation) {
  testing::ExpectRateJacobianMatchesNumeric(testing::kLinearAcceleration,
                                            TrajectoryModel::kSE3,
                                            GetParam(),
                                            {55u, 56u},
                                            1e-14,
                                            kJacobianTolerance);
}

// Rotation steps between control poses: tiny (series branches), generic, large.
INSTANTIATE_TEST_SUITE_P(RotationSteps,
                         SE3SplineJacobian,
                         ::testing::Values(std::make_pair(1e-9, 1e-6),
                                           std::make_pair(0.1, 1.0),
                                           std::make_pair(2.5, 3.0)));

// ---------------------------------------------------------------------------------------------
// The same template with ceres::Jet.

TEST(SE3Spline, JetTimeDerivativeIsVelocity) {
  using Jet = ceres::Jet<double, 1>;
  const SE3Splined spline = MakeRandomSpline(61);
  std::vector<SE3<Jet>> poses;
  for (const SE3d& pose : spline.control_poses()) poses.push_back(pose.cast<Jet>());
  const SE3Spline<Jet> jet_spline(poses, spline.t0_ns(), spline.dt_ns());
  for (double t : InteriorTimes(spline)) {
    SE3<Jet> T_w_s;
    Vector3<Jet> w_s;
    jet_spline.Evaluate(jet_spline.SegmentAt(Jet(t, 0)), &T_w_s, &w_s);
    const State s = EvaluateAt(spline, t);
    Eigen::Vector3d dp_dt, dw_dt;
    for (int r = 0; r < 3; ++r) {
      dp_dt[r] = T_w_s.translation()[r].v[0];
      dw_dt[r] = w_s[r].v[0];
    }
    EXPECT_TRUE(RelativelyNear(dp_dt, s.v_w, 1e-12)) << t;
    EXPECT_TRUE(RelativelyNear(dw_dt, s.w_dot_s, 1e-12)) << t;
  }
}

}  // namespace
}  // namespace splinecal

namespace splinecal {
namespace {

// The named accessors return exactly what the one-pass Evaluate writes for that output.
TEST(SE3Spline, NamedAccessorsEqualEvaluate) {
  const SE3Splined spline(
      testing::RandomControlPoses(8, 17), testing::kEurocLikeT0Ns, testing::kTestDtNs);
  for (double t = spline.start_time(); t <= spline.end_time(); t += 0.0731) {
    const Segment<double> segment = spline.SegmentAt(t);
    SE3d T_w_s;
    Eigen::Vector3d w_s, w_dot_s, v_w, a_w;
    spline.Evaluate(segment, &T_w_s, &w_s, &w_dot_s, &v_w, &a_w);
    EXPECT_EQ(spline.Pose(segment).matrix(), T_w_s.matrix());
    EXPECT_EQ(spline.AngularVelocity(segment), w_s);
    EXPECT_EQ(spline.AngularAcceleration(segment), w_dot_s);
    EXPECT_EQ(spline.LinearVelocity(segment), v_w);
    EXPECT_EQ(spline.LinearAcceleration(segment), a_w);
  }
}

}  // namespace
}  // namespace splinecal
