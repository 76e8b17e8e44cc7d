// The split SO(3) x R^3 spline's Jacobians (spline/split_segment_jacobians.h) in splinecal's
// tangent (control pose T_k Exp([rho; phi])): against central differences and Ridders'
// extrapolation of the spline under that perturbation, and against the reference split spline
// of the benchmark, whose tangent is (p + dp, R Exp(dphi)): d/d rho_k = d/d p_k R_k.
#include "splinecal/spline/split_segment_jacobians.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <initializer_list>
#include <utility>
#include <vector>

#include "spline/reference_split_spline.h"
#include "spline/spline_checks.h"
#include "spline/spline_test_util.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

using testing::RelativelyNear;

// Central differences (h = 1e-5) on outputs of O(1..100): errors ~1e-10 absolute; 1e-6 relative
// leaves margin and still catches any wrong term (those are O(1) relative).
constexpr double kJacobianTolerance = 1e-6;
// Ridders' extrapolation is accurate to ~1e-12 on smooth functions (testing/numeric_diff.h).
constexpr double kRiddersTolerance = 1e-9;
// The reference evaluates the same derivatives by other formulas (Jr^-1 chained instead of the
// U, V polynomials; rotation matrices multiplied in another order).
constexpr double kSameModelTolerance = 1e-12;

SE3Splined MakeRandomSplit(uint32_t seed, double min_angle, double max_angle) {
  return testing::RandomSpline(seed, TrajectoryModel::kSplitSO3R3, min_angle, max_angle);
}

// Every segment's knots (u = 0, 1) included: the Jacobians need no room for steps in time.
constexpr std::initializer_list<double> kSegmentFractions = {0.0, 0.013, 0.25, 0.5, 0.81, 1.0};

std::vector<double> SampleTimes(const SE3Splined& spline) {
  return testing::InteriorTimes(spline, kSegmentFractions);
}

// Rotation steps between control poses: tiny (series branches), generic, large.
class SplitJacobian : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(SplitJacobian, PoseMatchesNumericRightPerturbation) {
  testing::ExpectPoseJacobianMatchesNumeric(
      TrajectoryModel::kSplitSO3R3,
      GetParam(),
      {21u, 22u},
      0.0,
      kJacobianTolerance,
      kSegmentFractions,
      [](const ControlPoseJacobian<6>& J) {
        for (int k = 0; k < 4; ++k) {
          // Position and orientation do not mix (split_segment_jacobians.h, step 2).
          EXPECT_TRUE(J.blocks[k].topRightCorner(3, 3).isZero(0.0));
          EXPECT_TRUE(J.blocks[k].bottomLeftCorner(3, 3).isZero(0.0));
        }
      });
}

TEST_P(SplitJacobian, AngularVelocityMatchesNumericRightPerturbation) {
  testing::ExpectRateJacobianMatchesNumeric(testing::kAngularVelocity,
                                            TrajectoryModel::kSplitSO3R3,
                                            GetParam(),
                                            {23u},
                                            0.0,
                                            kJacobianTolerance,
                                            kSegmentFractions);
}

TEST_P(SplitJacobian, LinearAccelerationMatchesNumericRightPerturbation) {
  testing::ExpectRateJacobianMatchesNumeric(testing::kLinearAcceleration,
                                            TrajectoryModel::kSplitSO3R3,
                                            GetParam(),
                                            {25u},
                                            0.0,
                                            kJacobianTolerance,
                                            kSegmentFractions);
}

TEST_P(SplitJacobian, SpecificForceMatchesNumericRightPerturbation) {
  const auto [min_angle, max_angle] = GetParam();
  const SE3Splined spline = MakeRandomSplit(27, min_angle, max_angle);
  const Eigen::Vector3d g_w(0.4, -0.3, -9.8);
  const Eigen::Vector3d b_a(0.05, -0.02, 0.1);
  for (double t : SampleTimes(spline)) {
    const Segment<double> seg = spline.SegmentAt(t);
    Eigen::Vector3d accel;
    ControlPoseJacobian<3> J;
    Eigen::Matrix3d J_gw;
    PredictAccelWithJacobian(spline, seg, g_w, b_a, &accel, &J, &J_gw);
    Eigen::Vector3d accel_value, unused;
    PredictImu(spline, seg, g_w, b_a, b_a, &unused, &accel_value);
    EXPECT_TRUE(RelativelyNear(accel, accel_value, 1e-13));
    EXPECT_TRUE(RelativelyNear(J_gw, -spline.Pose(seg).rotationMatrix().transpose(), 1e-14));
    EXPECT_TRUE(testing::ControlJacobianMatchesNumeric(
        J,
        spline,
        seg,
        [&](const SE3Splined& s) {
          Eigen::Vector3d a;
          PredictImu(s, seg, g_w, b_a, b_a, &unused, &a);
          return Eigen::VectorXd(a);
        },
        kJacobianTolerance))
        << "t " << t;
  }
}

INSTANTIATE_TEST_SUITE_P(RotationSteps,
                         SplitJacobian,
                         ::testing::Values(std::make_pair(1e-9, 1e-6),
                                           std::make_pair(0.1, 1.0),
                                           std::make_pair(2.5, 3.0)));

// Ridders' extrapolation pins the pose and specific-force Jacobians to ~1e-9 at generic steps.
TEST(SplitJacobian, PoseAndSpecificForceMatchRiddersExtrapolation) {
  const SE3Splined spline = MakeRandomSplit(29, 0.3, 1.5);
  const Eigen::Vector3d g_w(0.0, 0.0, -9.81);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (double t : {0.31, 0.47, 0.66}) {
    const Segment<double> seg = spline.SegmentAt(t);
    SE3d T_w_s;
    ControlPoseJacobian<6> J_pose;
    spline.EvaluatePoseJacobian(seg, &T_w_s, &J_pose);
    ControlPoseJacobian<3> J_accel;
    Eigen::Vector3d accel;
    PredictAccelWithJacobian(spline, seg, g_w, zero, &accel, &J_accel);
    for (int k = 0; k < 4; ++k) {
      const int index = seg.first_index() + k;
      const Eigen::MatrixXd J_pose_num = testing::RiddersJacobian(
          [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
            return (T_w_s.inverse() * testing::PerturbedControlPose(spline, index, d).Pose(seg))
                .Log();
          },
          Eigen::VectorXd::Zero(6));
      const Eigen::MatrixXd J_accel_num = testing::RiddersJacobian(
          [&](const Eigen::VectorXd& d) -> Eigen::VectorXd {
            Eigen::Vector3d gyro, a;
            PredictImu(
                testing::PerturbedControlPose(spline, index, d), seg, g_w, zero, zero, &gyro, &a);
            return a;
          },
          Eigen::VectorXd::Zero(6));
      EXPECT_TRUE(RelativelyNear(J_pose.blocks[k], J_pose_num, kRiddersTolerance)) << t << k;
      EXPECT_TRUE(RelativelyNear(J_accel.blocks[k], J_accel_num, kRiddersTolerance)) << t << k;
    }
  }
}

// Against the reference split spline: its rotation columns are ours, its position columns
// (d/d p_k) are ours times R_k^T.
TEST(SplitJacobian, ResidualJacobiansMatchTheReferenceSplitSpline) {
  for (const auto& [min_angle, max_angle] :
       {std::make_pair(1e-9, 1e-6), std::make_pair(0.1, 1.0), std::make_pair(2.5, 3.0)}) {
    const SE3Splined spline = MakeRandomSplit(31, min_angle, max_angle);
    const reference::SplitSpline ref =
        testing::ReferenceSplitSpline(spline, reference::KnotMode::kCached);
    const Eigen::Vector3d g_w(0.3, -0.2, -9.81);
    const Eigen::Vector3d bias(0.01, -0.02, 0.03);
    const Eigen::Vector3d measured(0.1, -0.2, 9.7);
    for (double t : SampleTimes(spline)) {
      const Segment<double> seg = spline.SegmentAt(t);
      const reference::Query query =
          ref.QueryAtNs(spline.knot_time_ns(seg.index) + std::llround(seg.u * spline.dt_ns()));
      ASSERT_NEAR(query.u, seg.u, 1e-9);
      reference::ResidualJacobians J_ref;
      Eigen::Vector3d r_ref;
      Eigen::Vector3d accel;
      ControlPoseJacobian<3> J;
      Eigen::Matrix3d J_gw;
      const Segment<double> at_query = MakeSegment(query.index, query.u, spline.dt());
      ref.AccelResidual(query, measured, bias, g_w, &r_ref, &J_ref);
      PredictAccelWithJacobian(spline, at_query, g_w, bias, &accel, &J, &J_gw);
      EXPECT_TRUE(RelativelyNear(accel - measured, r_ref, kSameModelTolerance)) << t;
      EXPECT_TRUE(RelativelyNear(J_gw, J_ref.gravity, kSameModelTolerance)) << t;
      for (int k = 0; k < 4; ++k) {
        const Eigen::Matrix3d R_k = spline.control_pose(J.first_index + k).rotationMatrix();
        EXPECT_TRUE(RelativelyNear(J.blocks[k].leftCols<3>() * R_k.transpose(),
                                   J_ref.control[k].leftCols<3>(),
                                   kSameModelTolerance))
            << t << " " << k;
        EXPECT_TRUE(RelativelyNear(
            J.blocks[k].rightCols<3>(), J_ref.control[k].rightCols<3>(), kSameModelTolerance))
            << t << " " << k;
      }
      ControlPoseJacobian<3> J_gyro;
      Eigen::Vector3d gyro;
      PredictGyroWithJacobian(spline, at_query, bias, &gyro, &J_gyro);
      ref.GyroResidual(query, measured, bias, &r_ref, &J_ref);
      EXPECT_TRUE(RelativelyNear(gyro - measured, r_ref, kSameModelTolerance)) << t;
      for (int k = 0; k < 4; ++k) {
        EXPECT_TRUE(RelativelyNear(J_gyro.blocks[k], J_ref.control[k], kSameModelTolerance));
      }
    }
  }
}

}  // namespace
}  // namespace splinecal
