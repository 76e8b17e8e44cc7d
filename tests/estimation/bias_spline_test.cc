#include "splinecal/estimation/bias_spline.h"

#include <gtest/gtest.h>

#include <numeric>
#include <vector>

namespace splinecal {
namespace {

KnotLayout PoseLayout() {
  KnotLayout layout;
  layout.t0_ns = 5'000'000'000;
  layout.dt_ns = 50'000'000;  // 0.05 s
  layout.num_control_poses = 203;  // valid range 10 s
  return layout;
}

TEST(BiasSpline, ConstantHasOnePointWithWeightOne) {
  const BiasSpline bias(BiasModel::kConstant, PoseLayout(), 1.0);
  EXPECT_EQ(bias.num_points(), 1);
  EXPECT_EQ(bias.points_per_segment(), 1);
  const BiasWeights w = bias.WeightsAt(PoseLayout().start_time_ns() + 12345);
  EXPECT_EQ(w.first_point, 0);
  EXPECT_EQ(w.weights[0], 1.0);
  const double values[3] = {0.1, 0.2, 0.3};
  EXPECT_EQ(bias.Evaluate(values, 0), Eigen::Vector3d(0.1, 0.2, 0.3));
}

TEST(BiasSpline, KnotsAreWholePoseIntervalsStartingAtTheValidRange) {
  const KnotLayout pose = PoseLayout();
  const BiasSpline bias(BiasModel::kSpline, pose, 0.98);  // rounds to 20 intervals = 1 s
  EXPECT_EQ(bias.dt_ns(), 1'000'000'000);
  EXPECT_EQ(bias.t0_ns() + bias.dt_ns(), pose.start_time_ns());
  // 10 s span: 10 segments need 13 control points.
  EXPECT_EQ(bias.num_points(), 13);
}

// Every pose segment lies inside the bias segment SegmentOfPoseSegment gives: the weights found
// through the pose segment equal those found from the time alone, and sum to one.
TEST(BiasSpline, PoseSegmentsLieInsideTheirBiasSegment) {
  const KnotLayout pose = PoseLayout();
  const BiasSpline bias(BiasModel::kSpline, pose, 0.7);
  for (int64_t t = pose.start_time_ns(); t <= pose.end_time_ns(); t += 3'333'333) {
    SegmentPosition position;
    ASSERT_TRUE(pose.SegmentAtNs(t, &position));
    const BiasWeights by_segment =
        bias.WeightsInSegment(t, bias.SegmentOfPoseSegment(position.index));
    const BiasWeights by_time = bias.WeightsAt(t);
    const double sum = std::accumulate(by_time.weights.begin(), by_time.weights.end(), 0.0);
    EXPECT_NEAR(sum, 1.0, 1e-12);
    // The same point in the spline: either the same segment and weights, or at a bias knot,
    // adjacent segments whose weights give the same combination.
    std::vector<double> a_segment(bias.num_points(), 0.0);
    std::vector<double> a_time(bias.num_points(), 0.0);
    for (int j = 0; j < 4; ++j) {
      a_segment[by_segment.first_point + j] += by_segment.weights[j];
      a_time[by_time.first_point + j] += by_time.weights[j];
    }
    for (int m = 0; m < bias.num_points(); ++m) EXPECT_NEAR(a_segment[m], a_time[m], 1e-12) << t;
  }
}

}  // namespace
}  // namespace splinecal
