// The trajectory model's names (spline/trajectory_model.h) and the evaluation that follows it
// (spline/trajectory_evaluation.h, SE3Spline::model()).
#include "splinecal/spline/trajectory_model.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <vector>

#include "spline/spline_test_util.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/split_segment.h"
#include "splinecal/spline/split_segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {
namespace {

TEST(TrajectoryModel, NamesRoundTrip) {
  for (TrajectoryModel model : {TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3}) {
    TrajectoryModel parsed = TrajectoryModel::kSE3;
    ASSERT_TRUE(ParseTrajectoryModel(TrajectoryModelName(model), &parsed));
    EXPECT_EQ(parsed, model);
  }
  EXPECT_STREQ(TrajectoryModelName(TrajectoryModel::kSE3), "se3");
  EXPECT_STREQ(TrajectoryModelName(TrajectoryModel::kSplitSO3R3), "split");
}

TEST(TrajectoryModel, UnknownNamesAreRefusedAndLeaveTheValue) {
  TrajectoryModel model = TrajectoryModel::kSplitSO3R3;
  for (const char* name : {"", "SE3", "Split", "so3xr3", "split ", "coupled"}) {
    EXPECT_FALSE(ParseTrajectoryModel(name, &model)) << name;
    EXPECT_EQ(model, TrajectoryModel::kSplitSO3R3);
  }
}

TEST(TrajectoryModel, SplineDefaultsToTheCoupledModel) {
  const SE3Splined spline(
      testing::RandomControlPoses(6, 1), testing::kEurocLikeT0Ns, testing::kTestDtNs);
  EXPECT_EQ(spline.model(), TrajectoryModel::kSE3);
}

// SE3Spline's evaluations and Jacobians are the model's own functions on its knot caches.
TEST(TrajectoryModel, SplineEvaluatesWithItsModel) {
  const std::vector<SE3d> poses = testing::RandomControlPoses(6, 2);
  for (TrajectoryModel model : {TrajectoryModel::kSE3, TrajectoryModel::kSplitSO3R3}) {
    const SE3Splined spline(poses, testing::kEurocLikeT0Ns, testing::kTestDtNs, model);
    EXPECT_EQ(spline.model(), model);
    const bool split = model == TrajectoryModel::kSplitSO3R3;
    for (double t = spline.start_time(); t <= spline.end_time(); t += 0.0731) {
      const Segment<double> seg = spline.SegmentAt(t);
      const SegmentKnots<double> knots = spline.Knots(seg);
      SE3d T_a, T_b;
      Eigen::Vector3d v_a, v_b, a_a, a_b;
      spline.Evaluate(seg, &T_a, nullptr, nullptr, &v_a, &a_a);
      if (split) {
        EvaluateSplitSegment(knots, seg, &T_b, nullptr, nullptr, &v_b, &a_b);
      } else {
        EvaluateSegment(knots, seg, &T_b, nullptr, nullptr, &v_b, &a_b);
      }
      EXPECT_EQ(T_a.matrix(), T_b.matrix());
      EXPECT_EQ(v_a, v_b);
      EXPECT_EQ(a_a, a_b);
      ControlPoseJacobian<6> J_a, J_b;
      spline.EvaluatePoseJacobian(seg, nullptr, &J_a);
      if (split) {
        EvaluateSplitPoseJacobian(knots, seg, nullptr, &J_b);
      } else {
        EvaluatePoseJacobian(knots, seg, nullptr, &J_b);
      }
      for (int k = 0; k < 4; ++k) EXPECT_EQ(J_a.blocks[k], J_b.blocks[k]);
    }
  }
}

// Copies and SetControlPose keep the model.
TEST(TrajectoryModel, CopiesAndUpdatesKeepTheModel) {
  SE3Splined spline(testing::RandomControlPoses(6, 3),
                    testing::kEurocLikeT0Ns,
                    testing::kTestDtNs,
                    TrajectoryModel::kSplitSO3R3);
  spline.SetControlPose(2, SE3d());
  spline.SetControlPoses(spline.control_poses());
  const SE3Splined copy = spline;
  EXPECT_EQ(copy.model(), TrajectoryModel::kSplitSO3R3);
}

}  // namespace
}  // namespace splinecal
