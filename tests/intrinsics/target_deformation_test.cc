// The target shape's basis, normalisation and reported heights (intrinsics/target_deformation.h).
#include "splinecal/intrinsics/target_deformation.h"

#include <gtest/gtest.h>

#include <cmath>

#include "splinecal/error.h"

namespace splinecal {
namespace {

TEST(TargetDeformation, NamesAndSizes) {
  EXPECT_STREQ(TargetDeformationName(TargetDeformationKind::kNone), "none");
  EXPECT_STREQ(TargetDeformationName(TargetDeformationKind::kQuadratic), "quadratic");
  EXPECT_STREQ(TargetDeformationName(TargetDeformationKind::kCubic), "cubic");
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kNone), 0);
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kQuadratic), 3);
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kCubic), 7);
}

TEST(TargetDeformation, NormalisesToTheTargetsBoundingBox) {
  // 6 x 6 tags of 0.088 m with 0.3 spacing: corners from 0 to 6 * 0.088 * 1.3 - 0.3 * 0.088.
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const TargetShape shape = MakeTargetShape(target, TargetDeformationKind::kCubic);
  const double side = 6 * 0.088 * 1.3 - 0.3 * 0.088;
  EXPECT_NEAR(shape.half_extent, 0.5 * side, 1e-12);
  EXPECT_NEAR(shape.centre.x(), 0.5 * side, 1e-12);
  EXPECT_NEAR(shape.centre.y(), 0.5 * side, 1e-12);
  // At the corner (x0 + a, y0 - a): s = 1, t = -1.
  const double c[7] = {1, 2, 3, 4, 5, 6, 7};
  const Eigen::Vector3d p = shape.Deform(
      Eigen::Vector3d(shape.centre.x() + shape.half_extent, shape.centre.y() - shape.half_extent,
                      0.0),
      c);
  EXPECT_NEAR(p.z(), 1 - 2 + 3 + 4 - 5 + 6 - 7, 1e-12);
  // The centre stays where it is: no constant term (the gauge).
  EXPECT_EQ(shape.Deform(Eigen::Vector3d(shape.centre.x(), shape.centre.y(), 0.0), c).z(), 0.0);
}

TEST(TargetDeformation, RejectsATargetOutOfItsPlane) {
  CalibrationTarget target = MakeAprilGrid(2, 2, 0.088, 0.3);
  target.points.begin()->second.z() = 0.01;
  EXPECT_THROW(MakeTargetShape(target, TargetDeformationKind::kQuadratic), Error);
  EXPECT_NO_THROW(MakeTargetShape(target, TargetDeformationKind::kNone));
}

TEST(TargetDeformation, HeightsAreRelativeToTheLeastSquaresPlane) {
  // A symmetric bowl h = 1 mm (s^2 + t^2) on a symmetric grid: its least-squares plane is level
  // at the mean height of the points, so the centre sits that mean below it and the corners
  // 2 mm minus the mean above it.
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const TargetShape shape = MakeTargetShape(target, TargetDeformationKind::kQuadratic);
  const double c[3] = {1e-3, 0.0, 1e-3};
  double mean = 0.0;
  for (const auto& [id, p] : target.points) mean += shape.Deform(p, c).z();
  mean /= static_cast<double>(target.points.size());
  const TargetDeformationHeights heights = MakeTargetDeformationHeights(target, shape);
  ASSERT_EQ(heights.M.rows(), 5);
  ASSERT_EQ(heights.M.cols(), 3);
  const Eigen::VectorXd h = heights.M * Eigen::Vector3d(c[0], c[1], c[2]);
  EXPECT_EQ(heights.names[0], "centre");
  EXPECT_NEAR(h(0), -mean, 1e-15);
  for (int i = 1; i < 5; ++i) EXPECT_NEAR(h(i), 2e-3 - mean, 1e-15) << heights.names[i];
  // A saddle s t: zero mean and no tilt on the grid, +-1 mm at the corners.
  const Eigen::VectorXd saddle = heights.M * Eigen::Vector3d(0.0, 1e-3, 0.0);
  EXPECT_NEAR(saddle(0), 0.0, 1e-15);
  EXPECT_NEAR(saddle(1), 1e-3, 1e-15);   // (-1, -1)
  EXPECT_NEAR(saddle(2), -1e-3, 1e-15);  // (+1, -1)
}

}  // namespace
}  // namespace splinecal
