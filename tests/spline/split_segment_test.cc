// The split SO(3) x R^3 spline's evaluation (spline/split_segment.h): its definition written out
// with lie/so3.h, its time derivatives against central differences, its rotation against the
// coupled spline's (bit for bit), and every value against the reference split spline of the
// benchmark (tests/spline/reference_split_spline.h, written independently from the formulas).
#include "splinecal/spline/split_segment.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "spline/reference_split_spline.h"
#include "spline/spline_checks.h"
#include "spline/spline_test_util.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace {

using testing::EvaluateAll;
using testing::EvaluateAt;
using testing::InteriorTimes;
using testing::RelativelyNear;

// The same formulas evaluated in another order (reference spline, Exp of lie/so3.h): a few dozen
// roundings on values of O(1..100).
constexpr double kSameModelTolerance = 1e-12;

constexpr int kNumPoses = testing::kRandomSplinePoses;

SE3Splined MakeSplit(const std::vector<SE3d>& poses) {
  return SE3Splined(
      poses, testing::kEurocLikeT0Ns, testing::kTestDtNs, TrajectoryModel::kSplitSO3R3);
}

SE3Splined MakeRandomSplit(uint32_t seed, double min_angle = 0.1, double max_angle = 1.0) {
  return testing::RandomSpline(seed, TrajectoryModel::kSplitSO3R3, min_angle, max_angle);
}

// Times in every segment, both ends and knots included.
std::vector<int64_t> SampleTimesNs(const SE3Splined& spline) {
  std::vector<int64_t> times;
  for (int i = 1; i + 2 < spline.num_control_poses(); ++i) {
    for (double u : {0.0, 0.013, 0.37, 0.5, 0.81, 0.99}) {
      times.push_back(spline.knot_time_ns(i) + static_cast<int64_t>(u * spline.dt_ns()));
    }
  }
  times.push_back(spline.end_time_ns());
  return times;
}

using State = testing::SplineState;

TEST(SplitSegment, PoseMatchesTheDefinitionWrittenWithSo3ExpAndLog) {
  const SE3Splined spline = MakeRandomSplit(3);
  const std::vector<SE3d>& P = spline.control_poses();
  for (int64_t t_ns : SampleTimesNs(spline)) {
    const Segment<double> seg = spline.SegmentAtNs(t_ns);
    const int i0 = seg.first_index();
    // R = R_0 prod_j Exp(Bt_j phi_j), phi_j = Log(R_{j-1}^T R_j); p = sum_j B_j p_j with the
    // ordinary B-spline weights B = M [1 u u^2 u^3]^T (M: rows of C differenced).
    SO3d R = P[i0].so3();
    for (int j = 1; j <= 3; ++j) {
      const Eigen::Vector3d phi = (P[i0 + j - 1].so3().inverse() * P[i0 + j].so3()).Log();
      R = R * SO3d::Exp(seg.b[j] * phi);
    }
    const Eigen::Matrix4d C = CumulativeBlendingMatrix();
    Eigen::Matrix4d M = C;
    for (int r = 0; r < 3; ++r) M.row(r) = C.row(r) - C.row(r + 1);
    const Eigen::Vector4d B = M * PowerBasis<0>(seg.u);
    Eigen::Vector3d p = Eigen::Vector3d::Zero();
    for (int j = 0; j < 4; ++j) p += B[j] * P[i0 + j].translation();
    const SE3d T_w_s = spline.Pose(seg);
    EXPECT_TRUE(RelativelyNear(T_w_s.rotationMatrix(), R.matrix(), kSameModelTolerance));
    EXPECT_TRUE(RelativelyNear(T_w_s.translation(), p, kSameModelTolerance)) << t_ns;
  }
}

TEST(SplitSegment, OrientationAndAngularRatesAreTheCoupledSplinesBitForBit) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(kNumPoses, 5);
  const SE3Splined split = MakeSplit(poses);
  const SE3Splined coupled(poses, split.t0_ns(), split.dt_ns());
  EXPECT_EQ(coupled.model(), TrajectoryModel::kSE3);
  for (int64_t t_ns : SampleTimesNs(split)) {
    const Segment<double> seg = split.SegmentAtNs(t_ns);
    SE3d T_split, T_coupled;
    Eigen::Vector3d w_split, w_coupled, w_dot_split, w_dot_coupled;
    split.Evaluate(seg, &T_split, &w_split, &w_dot_split);
    coupled.Evaluate(seg, &T_coupled, &w_coupled, &w_dot_coupled);
    EXPECT_EQ(T_split.so3().quaternion().coeffs(), T_coupled.so3().quaternion().coeffs());
    EXPECT_EQ(w_split, w_coupled);
    EXPECT_EQ(w_dot_split, w_dot_coupled);
  }
}

TEST(SplitSegment, TimeDerivativesMatchCentralDifferences) {
  testing::ExpectTimeDerivativesMatchCentralDifferences(MakeRandomSplit(7));
}

TEST(SplitSegment, BodyOutputsAreTheWorldOutputsRotated) {
  const SE3Splined spline = MakeRandomSplit(9);
  for (int64_t t_ns : SampleTimesNs(spline)) {
    const Segment<double> seg = spline.SegmentAtNs(t_ns);
    const SegmentKnots<double> knots = spline.Knots(seg);
    SE3d T_w_s;
    Eigen::Matrix3d R_w_s;
    Eigen::Vector3d w_s, w_dot_s, v_s, a_s, v_w, a_w;
    internal::EvaluateSplitSegmentBody(knots, seg, &T_w_s, &R_w_s, &w_s, &w_dot_s, &v_s, &a_s);
    EvaluateSplitSegment(knots, seg, nullptr, nullptr, nullptr, &v_w, &a_w);
    EXPECT_TRUE(RelativelyNear(R_w_s, T_w_s.rotationMatrix(), 1e-14));
    EXPECT_TRUE(RelativelyNear(R_w_s * v_s, v_w, 1e-13));
    EXPECT_TRUE(RelativelyNear(R_w_s * a_s, a_w, 1e-13));
  }
}

TEST(SplitSegment, IsC2ContinuousAcrossKnots) {
  const SE3Splined spline = MakeRandomSplit(11);
  for (int i = 2; i + 2 < spline.num_control_poses(); ++i) {
    const int64_t knot_ns = spline.knot_time_ns(i);
    // The end of segment i-1 (u = 1) against the start of segment i (u = 0).
    const Segment<double> before = MakeSegment(i - 1, 1.0, spline.dt());
    const Segment<double> after = spline.SegmentAtNs(knot_ns);
    ASSERT_EQ(after.index, i);
    const State a = EvaluateAll(spline, before);
    const State b = EvaluateAll(spline, after);
    EXPECT_TRUE(RelativelyNear(a.T_w_s.matrix(), b.T_w_s.matrix(), 1e-12));
    EXPECT_TRUE(RelativelyNear(a.v_w, b.v_w, 1e-12));
    EXPECT_TRUE(RelativelyNear(a.a_w, b.a_w, 1e-12));
    EXPECT_TRUE(RelativelyNear(a.w_dot_s, b.w_dot_s, 1e-12));
  }
}

// With equal rotations both models reduce to the cubic B-spline of the positions (the coupled
// spline's Omega_k is then [R^T dp_k; 0], se3_spline_test.cc PureTranslationIsScalarCubicBSpline).
TEST(SplitSegment, EqualRotationsGiveTheCoupledSplinesPositions) {
  std::vector<SE3d> poses = testing::RandomControlPoses(kNumPoses, 13);
  const SO3d R = poses[0].so3();
  for (SE3d& T : poses) T = SE3d(R, T.translation());
  const SE3Splined split = MakeSplit(poses);
  const SE3Splined coupled(poses, split.t0_ns(), split.dt_ns());
  for (int64_t t_ns : SampleTimesNs(split)) {
    const Segment<double> seg = split.SegmentAtNs(t_ns);
    State a, b;
    split.Evaluate(seg, &a.T_w_s, &a.w_s, nullptr, &a.v_w, &a.a_w);
    coupled.Evaluate(seg, &b.T_w_s, &b.w_s, nullptr, &b.v_w, &b.a_w);
    EXPECT_TRUE(RelativelyNear(a.T_w_s.translation(), b.T_w_s.translation(), 1e-12));
    EXPECT_TRUE(RelativelyNear(a.v_w, b.v_w, 1e-12));
    EXPECT_TRUE(RelativelyNear(a.a_w, b.a_w, 1e-12));
    EXPECT_EQ(a.w_s, Eigen::Vector3d::Zero());
  }
}

TEST(SplitSegment, MatchesTheReferenceSplitSpline) {
  const SE3Splined spline = MakeRandomSplit(15, 0.1, 2.5);
  const reference::SplitSpline ref =
      testing::ReferenceSplitSpline(spline, reference::KnotMode::kPerQuery);
  const Eigen::Vector3d g_w(0.3, -0.2, -9.81);
  const Eigen::Vector3d b_g(0.01, -0.02, 0.03);
  const Eigen::Vector3d b_a(-0.1, 0.2, 0.05);
  for (int64_t t_ns : SampleTimesNs(spline)) {
    const Segment<double> seg = spline.SegmentAtNs(t_ns);
    const reference::Query query = ref.QueryAtNs(t_ns);
    State s;
    spline.Evaluate(seg, &s.T_w_s, &s.w_s, nullptr, nullptr, &s.a_w);
    Eigen::Matrix3d R_ref;
    Eigen::Vector3d p_ref, w_ref, a_ref, gyro_ref, accel_ref, gyro, accel;
    ref.Pose(query, &R_ref, &p_ref);
    ref.Rates(query, &w_ref, &a_ref);
    ref.PredictImu(query, g_w, b_g, b_a, &gyro_ref, &accel_ref);
    PredictImu(spline, seg, g_w, b_g, b_a, &gyro, &accel);
    EXPECT_TRUE(RelativelyNear(s.T_w_s.rotationMatrix(), R_ref, kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(s.T_w_s.translation(), p_ref, kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(s.w_s, w_ref, kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(s.a_w, a_ref, kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(gyro, gyro_ref, kSameModelTolerance)) << t_ns;
    EXPECT_TRUE(RelativelyNear(accel, accel_ref, kSameModelTolerance)) << t_ns;
  }
}

// A ceres::Jet time offset flows through u: the Jet parts of the pose are its time derivatives.
TEST(SplitSegment, JetTimeDerivativeIsVelocity) {
  using Jet = ceres::Jet<double, 1>;
  const SE3Splined spline = MakeRandomSplit(17);
  std::vector<SE3<Jet>> poses;
  for (const SE3d& pose : spline.control_poses()) poses.push_back(pose.cast<Jet>());
  const SE3Spline<Jet> jet_spline(
      poses, spline.t0_ns(), spline.dt_ns(), TrajectoryModel::kSplitSO3R3);
  for (double t : InteriorTimes(spline)) {
    SE3<Jet> T_w_s;
    Vector3<Jet> w_s;
    Vector3<Jet> v_w;
    jet_spline.Evaluate(jet_spline.SegmentAt(Jet(t, 0)), &T_w_s, &w_s, nullptr, &v_w);
    const State s = EvaluateAt(spline, t);
    Eigen::Vector3d dp_dt, dw_dt, dv_dt;
    for (int r = 0; r < 3; ++r) {
      dp_dt[r] = T_w_s.translation()[r].v[0];
      dw_dt[r] = w_s[r].v[0];
      dv_dt[r] = v_w[r].v[0];
    }
    EXPECT_TRUE(RelativelyNear(dp_dt, s.v_w, 1e-12)) << t;
    EXPECT_TRUE(RelativelyNear(dw_dt, s.w_dot_s, 1e-12)) << t;
    EXPECT_TRUE(RelativelyNear(dv_dt, s.a_w, 1e-12)) << t;
  }
}

// SegmentKnotData (four poses, no spline) gives the spline's own numbers.
TEST(SplitSegment, KnotDataFromFourPosesEqualsTheSplinesCaches) {
  const SE3Splined spline = MakeRandomSplit(19);
  for (int64_t t_ns : SampleTimesNs(spline)) {
    const Segment<double> seg = spline.SegmentAtNs(t_ns);
    const std::vector<SE3d>& P = spline.control_poses();
    const int i0 = seg.first_index();
    const SegmentKnotData<double> data(P[i0], P[i0 + 1], P[i0 + 2], P[i0 + 3], false, i0);
    SE3d T_a, T_b;
    Eigen::Vector3d a_a, a_b;
    EvaluateSplitSegment(data.knots(), seg, &T_a, nullptr, nullptr, nullptr, &a_a);
    spline.Evaluate(seg, &T_b, nullptr, nullptr, nullptr, &a_b);
    EXPECT_EQ(T_a.matrix(), T_b.matrix());
    EXPECT_EQ(a_a, a_b);
  }
}

}  // namespace
}  // namespace splinecal
