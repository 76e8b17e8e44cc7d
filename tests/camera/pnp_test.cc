#include "splinecal/camera/pnp.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "calib/camera_test_scene.h"
#include "camera/camera_test_models.h"
#include "splinecal/camera/target.h"

namespace splinecal {
namespace {

// Noise-free correspondences: the pose is recovered to the refinement's convergence (1e-9 m,
// 1e-9 rad are far below any use and far above rounding at a 1 m range).
constexpr double kExactTolerance = 1e-9;

struct Views {
  std::vector<Eigen::Vector3d> p_t;
  std::vector<Eigen::Vector2d> uv;
};

Views Project(const Camera& camera,
              const SE3d& T_c_t,
              const std::map<int64_t, Eigen::Vector3d>& points,
              double noise_px,
              unsigned seed) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> normal(0.0, noise_px > 0.0 ? noise_px : 1.0);
  Views v;
  for (const auto& [id, p] : points) {
    Eigen::Vector2d uv;
    if (!camera.Project(T_c_t * p, &uv) || !camera.InImage(uv)) continue;
    if (noise_px > 0.0) uv += Eigen::Vector2d(normal(rng), normal(rng));
    v.p_t.push_back(p);
    v.uv.push_back(uv);
  }
  return v;
}

SE3d TestPose(double tilt) {
  // Target about 0.8 m in front, tilted.
  return SE3d(SO3d::Exp(Eigen::Vector3d(tilt, -0.5 * tilt, 0.3)),
              Eigen::Vector3d(-0.2, -0.15, 0.8));
}

TEST(SolvePnp, PlanarTargetNoiseFreeIsExact) {
  const Camera camera = testing::EurocCamera();
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.05, 0.3);
  for (double tilt : {0.0, 0.3, 0.7}) {
    const SE3d T_c_t = TestPose(tilt);
    const Views v = Project(camera, T_c_t, target.points, 0.0, 1);
    ASSERT_GE(v.p_t.size(), 50u);
    const PnpResult result = SolvePnp(camera, v.p_t, v.uv);
    ASSERT_TRUE(result.ok) << result.message;
    const Vector6d error = (T_c_t.inverse() * result.T_c_t).Log();
    EXPECT_LT(error.head<3>().norm(), kExactTolerance) << tilt;
    EXPECT_LT(error.tail<3>().norm(), kExactTolerance) << tilt;
    EXPECT_LT(result.rms_px, 1e-8);
  }
}

TEST(SolvePnp, NonPlanarTargetNoiseFreeIsExact) {
  const Camera camera = testing::EurocCamera();
  std::map<int64_t, Eigen::Vector3d> points;
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-0.2, 0.2);
  for (int i = 0; i < 30; ++i) points[i] = Eigen::Vector3d(u(rng), u(rng), 0.5 * u(rng));
  const SE3d T_c_t(SO3d::Exp(Eigen::Vector3d(0.2, -0.1, 0.4)), Eigen::Vector3d(0.05, 0.02, 1.0));
  const Views v = Project(camera, T_c_t, points, 0.0, 1);
  const PnpResult result = SolvePnp(camera, v.p_t, v.uv);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_LT((T_c_t.inverse() * result.T_c_t).Log().norm(), kExactTolerance);
}

TEST(SolvePnp, NoisyPixelsGiveAPoseGoodEnoughToStartFrom) {
  // 0.5 px noise, ~100 corners at 0.8 m: the pose is good to ~1 mm and ~0.1 degree; the test
  // allows 5x that.
  const Camera camera = testing::EurocCamera();
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.05, 0.3);
  const SE3d T_c_t = TestPose(0.4);
  const Views v = Project(camera, T_c_t, target.points, 0.5, 9);
  const PnpResult result = SolvePnp(camera, v.p_t, v.uv);
  ASSERT_TRUE(result.ok) << result.message;
  const Vector6d error = (T_c_t.inverse() * result.T_c_t).Log();
  EXPECT_LT(error.head<3>().norm(), 5e-3);
  EXPECT_LT(error.tail<3>().norm(), 5 * 1.75e-3);
  EXPECT_NEAR(result.rms_px, 0.5 * std::sqrt(2.0), 0.1);  // RMS of 2-D errors
}

// A board whose corners were measured or refined sits slightly off any plane: EuRoC's AprilGrid,
// refined with every point free, has its corners about 1 mm RMS off the file's grid
// (docs/intrinsics.md, "Every point free"). The points are not at z = 0, so the DLT for
// non-planar targets applies, but at 0.4 px of noise the depth it needs is lost in the noise:
// such a board must still give the pose of the flat board's test above (same bounds, 5x the
// expected error).
TEST(SolvePnp, NearlyFlatMeasuredTargetGivesAPoseGoodEnoughToStartFrom) {
  const Camera camera = testing::EurocCamera();
  CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  std::mt19937 rng(3);
  std::normal_distribution<double> off_plane(0.0, 1e-3);
  for (auto& [id, p] : target.points) p.z() = off_plane(rng);
  for (double tilt : {0.0, 0.3, 0.6}) {
    for (unsigned seed = 1; seed <= 4; ++seed) {
      const SE3d T_c_t(SO3d::Exp(Eigen::Vector3d(tilt, -0.5 * tilt, 0.3)),
                       Eigen::Vector3d(-0.3, -0.25, 1.0));
      const Views v = Project(camera, T_c_t, target.points, 0.4, seed);
      ASSERT_GE(v.p_t.size(), 100u);
      const PnpResult result = SolvePnp(camera, v.p_t, v.uv);
      ASSERT_TRUE(result.ok) << result.message << " tilt " << tilt << " seed " << seed;
      const Vector6d error = (T_c_t.inverse() * result.T_c_t).Log();
      EXPECT_LT(error.head<3>().norm(), 5e-3) << tilt << " " << seed;
      EXPECT_LT(error.tail<3>().norm(), 5 * 1.75e-3) << tilt << " " << seed;
      EXPECT_NEAR(result.rms_px, 0.4 * std::sqrt(2.0), 0.1) << tilt << " " << seed;
    }
  }
}

// A flat target whose plane is not z = 0 (a points file in another frame) is planar for the
// closed form: exact without noise, where the DLT for non-planar targets is degenerate.
TEST(SolvePnp, FlatTargetOffTheXyPlaneNoiseFreeIsExact) {
  const Camera camera = testing::EurocCamera();
  const CalibrationTarget grid = MakeAprilGrid(6, 6, 0.05, 0.3);
  const SE3d T_other_t(SO3d::Exp(Eigen::Vector3d(0.4, -0.2, 1.0)), Eigen::Vector3d(0.1, 0.2, 0.3));
  std::map<int64_t, Eigen::Vector3d> points;
  for (const auto& [id, p] : grid.points) points[id] = T_other_t * p;
  const SE3d T_c_other = TestPose(0.3) * T_other_t.inverse();
  const Views v = Project(camera, T_c_other, points, 0.0, 1);
  ASSERT_GE(v.p_t.size(), 50u);
  const PnpResult result = SolvePnp(camera, v.p_t, v.uv);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_LT((T_c_other.inverse() * result.T_c_t).Log().norm(), kExactTolerance);
}

TEST(SolvePnp, EveryCameraModelNoiseFreeIsExact) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.05, 0.3);
  for (const testing::TestCamera& c : testing::AllTestCameras()) {
    const SE3d T_c_t = TestPose(0.3);
    const Views v = Project(c.camera, T_c_t, target.points, 0.0, 1);
    ASSERT_GE(v.p_t.size(), 50u) << c.label;
    const PnpResult result = SolvePnp(c.camera, v.p_t, v.uv);
    ASSERT_TRUE(result.ok) << c.label << ": " << result.message;
    EXPECT_LT((T_c_t.inverse() * result.T_c_t).Log().norm(), kExactTolerance) << c.label;
  }
}

TEST(SolvePnp, WideAngleTargetBesideTheCamera) {
  // A 190 degree double-sphere camera sees a target standing beside it, 0.6 m away towards the
  // image's corner (azimuth 45 degrees), from about 72 to 108 degrees off the optical axis: half
  // of its corners lie behind the image plane (z < 0), where no ray (x, y, 1) exists; bearings
  // carry them.
  const testing::TestCamera wide = testing::AllTestCameras().back();
  ASSERT_EQ(wide.camera.model_name(), "ds-none");
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.05, 0.3);
  const double s = std::sqrt(0.5);
  Eigen::Matrix3d R_c_t;  // target x along the optical axis, its normal towards the camera
  R_c_t.col(0) = Eigen::Vector3d::UnitZ();
  R_c_t.col(1) = Eigen::Vector3d(-s, s, 0.0);
  R_c_t.col(2) = Eigen::Vector3d(-s, -s, 0.0);
  const Eigen::Vector3d centre_t(0.1875, 0.1875, 0.0);  // the grid's centre (0.375 m across)
  const Eigen::Vector3d centre_c = 0.6 * Eigen::Vector3d(s, s, 0.0);
  const SE3d T_c_t(SO3d::FromMatrix(R_c_t), centre_c - R_c_t * centre_t);
  const Views v = Project(wide.camera, T_c_t, target.points, 0.0, 1);
  int behind = 0;
  for (const Eigen::Vector3d& p : v.p_t) behind += (T_c_t * p).z() < 0.0;
  ASSERT_GE(v.p_t.size(), 130u);
  ASSERT_GE(behind, 60);
  const PnpResult result = SolvePnp(wide.camera, v.p_t, v.uv);
  ASSERT_TRUE(result.ok) << result.message;
  EXPECT_LT((T_c_t.inverse() * result.T_c_t).Log().norm(), kExactTolerance);
}

TEST(SolvePnp, RefusesTooFewOrCollinearPoints) {
  const Camera camera = testing::EurocCamera();
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.05, 0.3);
  const SE3d T_c_t = TestPose(0.2);
  Views v = Project(camera, T_c_t, target.points, 0.0, 1);
  v.p_t.resize(5);
  v.uv.resize(5);
  PnpResult result = SolvePnp(camera, v.p_t, v.uv);
  EXPECT_FALSE(result.ok);
  EXPECT_THAT(result.message, ::testing::HasSubstr("too few points"));
  // One row of corners: collinear.
  std::map<int64_t, Eigen::Vector3d> row;
  for (int i = 0; i < 10; ++i) row[i] = Eigen::Vector3d(0.05 * i, 0.0, 0.0);
  v = Project(camera, T_c_t, row, 0.0, 1);
  result = SolvePnp(camera, v.p_t, v.uv);
  EXPECT_FALSE(result.ok);
  EXPECT_THAT(result.message, ::testing::HasSubstr("collinear"));
}

}  // namespace
}  // namespace splinecal
