// The target shape's basis, normalisation and reported heights, and the in-plane layout map
// (intrinsics/target_deformation.h).
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
  EXPECT_STREQ(TargetDeformationName(TargetDeformationKind::kInPlane), "in-plane");
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kNone), 0);
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kQuadratic), 3);
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kCubic), 7);
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kInPlane), 3);
  EXPECT_STREQ(TargetDeformationName(TargetDeformationKind::kInPlanePerView), "in-plane-per-view");
  EXPECT_EQ(TargetDeformationSize(TargetDeformationKind::kInPlanePerView), 2);
}

TEST(TargetDeformation, APerViewInsetIsTheInPlaneTagSizeOfOneView) {
  // (e1, e2) shared, d_v the view's own: the same point as the shared layout with d = d_v.
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const TargetShape shared = MakeTargetShape(target, TargetDeformationKind::kInPlane);
  const TargetShape per_view = MakeTargetShape(target, TargetDeformationKind::kInPlanePerView);
  EXPECT_TRUE(per_view.in_plane());
  EXPECT_TRUE(per_view.per_view_inset());
  EXPECT_FALSE(shared.per_view_inset());
  const double c[3] = {0.003, -0.002, -0.012};
  for (const auto& [id, p] : target.points) {
    EXPECT_NEAR((per_view.Deform(p, c, c[2]) - shared.Deform(p, c)).norm(), 0.0, 1e-15);
    EXPECT_NEAR((per_view.Displacement(p) - shared.Displacement(p)).norm(), 0.0, 1e-15);
  }
  // The shared layout ignores an inset.
  const Eigen::Vector3d p = *target.Find(13);
  EXPECT_EQ(shared.Deform(p, c, 0.5), shared.Deform(p, c));
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

// The distance between two target points after the in-plane map c.
double MovedDistance(const TargetShape& shape, const CalibrationTarget& target, int64_t a,
                     int64_t b, const double* c) {
  return (shape.Deform(*target.Find(a), c) - shape.Deform(*target.Find(b), c)).norm();
}

TEST(TargetDeformation, InPlaneScalesTheAxesShearsAndSizesTheTags) {
  // 6 x 6 tags of 0.088 m, 0.3 spacing: corner ids r * 12 + c on a 12 x 12 grid; tag 0 owns
  // 0, 1, 12, 13; corner 2 is tag 1's bottom left, one pitch (0.1144 m) right of corner 0.
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const TargetShape shape = MakeTargetShape(target, TargetDeformationKind::kInPlane);
  EXPECT_DOUBLE_EQ(shape.tag_size_m, 0.088);
  EXPECT_DOUBLE_EQ(shape.tag_pitch_m, 1.3 * 0.088);
  const double pitch = 1.3 * 0.088;
  const double side = 0.088;
  const double span = 5 * pitch;  // corner 0 to corner 10 (tag 5's bottom left)
  // d: a tag's side grows by 1 + d, the pitch between the same corners of two tags does not.
  const double d[3] = {0.0, 0.0, 0.01};
  EXPECT_NEAR(MovedDistance(shape, target, 0, 1, d), 1.01 * side, 1e-12);
  EXPECT_NEAR(MovedDistance(shape, target, 0, 12, d), 1.01 * side, 1e-12);
  EXPECT_NEAR(MovedDistance(shape, target, 0, 2, d), pitch, 1e-12);
  EXPECT_NEAR(MovedDistance(shape, target, 0, 24, d), pitch, 1e-12);
  // e1: x longer by 1 + e1, y shorter by 1 - e1.
  const double e1[3] = {0.002, 0.0, 0.0};
  EXPECT_NEAR(MovedDistance(shape, target, 0, 10, e1), 1.002 * span, 1e-12);
  EXPECT_NEAR(MovedDistance(shape, target, 0, 120, e1), 0.998 * span, 1e-12);
  // e2: the diagonal x = y longer by 1 + e2 (to first order), the axes unchanged to first order.
  const double e2[3] = {0.0, 0.002, 0.0};
  EXPECT_NEAR(MovedDistance(shape, target, 0, 130, e2), 1.002 * std::sqrt(2.0) * span, 1e-8);
  EXPECT_NEAR(MovedDistance(shape, target, 0, 10, e2), span, 1e-5 * span);
  // The centre of the target stays, and every point stays in the plane z = 0.
  const double all[3] = {0.003, -0.002, 0.01};
  for (const auto& [id, p] : target.points) EXPECT_EQ(shape.Deform(p, all).z(), 0.0);
  // e1 and e2 hold the target's centre (u = 0), d every tag's centre (o = 0).
  const Eigen::Vector3d centre(shape.centre.x(), shape.centre.y(), 0.0);
  EXPECT_NEAR(shape.Displacement(centre).leftCols(2).norm(), 0.0, 1e-15);
  const Eigen::Vector3d tag_centre(pitch + 0.5 * side, 0.5 * side, 0.0);
  EXPECT_NEAR(shape.Displacement(tag_centre).col(2).norm(), 0.0, 1e-15);
  // No heights to report in plane.
  const TargetDeformationHeights heights = MakeTargetDeformationHeights(target, shape);
  EXPECT_TRUE(heights.names.empty());
  EXPECT_EQ(heights.M.rows(), 0);
  EXPECT_EQ(heights.M.cols(), 3);
}

TEST(TargetDeformation, InPlaneNeedsAnAprilGridWithTagsApart) {
  EXPECT_THROW(MakeTargetShape(MakeCheckerboard(6, 5, 0.04, 0.04), TargetDeformationKind::kInPlane),
               Error);
  EXPECT_THROW(MakeTargetShape(MakeAprilGrid(3, 3, 0.088, 0.0), TargetDeformationKind::kInPlane),
               Error);
  CalibrationTarget moved = MakeAprilGrid(3, 3, 0.088, 0.3);
  moved.points.begin()->second.x() += 0.01;
  EXPECT_THROW(MakeTargetShape(moved, TargetDeformationKind::kInPlane), Error);
  EXPECT_NO_THROW(MakeTargetShape(moved, TargetDeformationKind::kQuadratic));
}

}  // namespace
}  // namespace splinecal
