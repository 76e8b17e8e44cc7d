// The free target's figure (report/target_points_figure.h): every point drawn, an arrow per free
// point at a round magnification, the offsets along the normal with their stds.
#include "splinecal/report/target_points_figure.h"

#include <gtest/gtest.h>

#include <cmath>

namespace splinecal {
namespace {

TEST(TargetPointsFigure, EveryPointAnArrowPerFreePointAndTheHeights) {
  TargetDeformationResult d;
  d.shape.kind = TargetDeformationKind::kPoints;
  d.refined_target.type = "points";
  // A 1 m square; points 0-2 free, 3 held at the file's position.
  const Eigen::Vector3d file[4] = {
      {0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}, {0.0, 1.0, 0.0}, {1.0, 1.0, 0.0}};
  const Eigen::Vector3d offset[3] = {{1e-3, 0.0, 2e-4}, {0.0, -2e-3, -1e-4}, {0.0, 0.0, 0.0}};
  for (int i = 0; i < 4; ++i) {
    d.refined_target.points[i] = file[i] + (i < 3 ? offset[i] : Eigen::Vector3d::Zero());
    if (i < 3) {
      d.point_offsets_m[i] = offset[i];
      d.point_offsets_std_m[i] = Eigen::Vector3d(1e-4, 1e-4, 5e-5);
    }
  }
  const plot::Figure figure = TargetPointsFigure(d);
  ASSERT_EQ(figure.panels.size(), 2u);
  // The longest in-plane offset (2 mm) drawn at about a twentieth of the 1 m width: 0.05 / 2e-3
  // = 25, rounded down to 20.
  EXPECT_NE(figure.panels[0].title.find("x 20"), std::string::npos) << figure.panels[0].title;
  const plot::Series& points = figure.panels[0].series[0];
  ASSERT_EQ(points.x.size(), 4u);
  for (int i = 0; i < 4; ++i) {
    EXPECT_DOUBLE_EQ(points.x[i], file[i].x());
    EXPECT_DOUBLE_EQ(points.y[i], file[i].y());
  }
  // Three arrows, each its start, its magnified tip and a NaN break.
  const plot::Series& arrows = figure.panels[0].series[1];
  ASSERT_EQ(arrows.x.size(), 9u);
  EXPECT_DOUBLE_EQ(arrows.y[4], 1.0 * 0.0 + 20.0 * -2e-3 + 0.0);  // point 1's tip
  EXPECT_TRUE(std::isnan(arrows.x[2]));
  const plot::Series& heights = figure.panels[1].series[0];
  ASSERT_EQ(heights.y.size(), 3u);
  EXPECT_NEAR(heights.y[0], 0.2, 1e-12);  // mm
  EXPECT_NEAR(heights.y_high[1] - heights.y_low[1], 0.1, 1e-12);
}

// From the test of the file's layout: the tested points, their one-step displacements as the
// arrows and heights, their stds as the bars.
TEST(TargetPointsFigure, TheFilesTestDrawsItsOneStepDisplacements) {
  TargetPointsCheck check;
  check.file_points_m = {{4, {0.0, 0.0, 0.0}}, {9, {0.5, 0.0, 0.0}}};
  check.offsets_m = {{4, {0.0, 1e-3, 3e-4}}, {9, {-1e-3, 0.0, 0.0}}};
  check.offsets_std_m = {{4, {1e-4, 1e-4, 2e-4}}, {9, {1e-4, 1e-4, 1e-4}}};
  const plot::Figure figure = TargetPointsFigure(check);
  ASSERT_EQ(figure.panels.size(), 2u);
  EXPECT_NE(figure.title.find("one step"), std::string::npos);
  const plot::Series& points = figure.panels[0].series[0];
  ASSERT_EQ(points.x.size(), 2u);
  EXPECT_DOUBLE_EQ(points.x[1], 0.5);  // the file's position, not the displaced one
  // 0.05 * 0.5 m / 1 mm = 25 -> x 20: point 4's tip 20 mm up.
  const plot::Series& arrows = figure.panels[0].series[1];
  ASSERT_EQ(arrows.y.size(), 6u);
  EXPECT_NEAR(arrows.y[1], 20.0 * 1e-3, 1e-12);
  const plot::Series& heights = figure.panels[1].series[0];
  ASSERT_EQ(heights.y.size(), 2u);
  EXPECT_NEAR(heights.y[0], 0.3, 1e-12);
  EXPECT_NEAR(heights.y_high[0] - heights.y_low[0], 0.4, 1e-12);
}

}  // namespace
}  // namespace splinecal
