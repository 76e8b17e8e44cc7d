#include "splinecal/io/target_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "testing/refusals.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

TEST(ReadTargetYaml, AprilGridCornersAsKalibrNumbersThem) {
  testing::TempDir dir;
  const CalibrationTarget target = ReadTargetYaml(dir.Write(
      "april.yaml",
      "target_type: 'aprilgrid'\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.3\n"));
  EXPECT_EQ(target.type, "aprilgrid");
  ASSERT_EQ(target.points.size(), 144u);  // 12 x 12 corners
  EXPECT_TRUE(target.IsPlanar());
  // Tag 0 owns corners 0, 1, 12, 13 (bottom-left, bottom-right, top-left, top-right).
  EXPECT_EQ(*target.Find(0), Eigen::Vector3d(0.0, 0.0, 0.0));
  EXPECT_NEAR((*target.Find(1) - Eigen::Vector3d(0.088, 0.0, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((*target.Find(12) - Eigen::Vector3d(0.0, 0.088, 0.0)).norm(), 0.0, 1e-15);
  EXPECT_NEAR((*target.Find(13) - Eigen::Vector3d(0.088, 0.088, 0.0)).norm(), 0.0, 1e-15);
  // Tag 1's first corner: one pitch (1.3 tagSize) to the right.
  EXPECT_NEAR((*target.Find(2) - Eigen::Vector3d(0.1144, 0.0, 0.0)).norm(), 0.0, 1e-15);
  // The last corner: 5 pitches + one tag.
  EXPECT_NEAR((*target.Find(143) - Eigen::Vector3d(0.66, 0.66, 0.0)).norm(), 0.0, 1e-14);
  EXPECT_EQ(target.Find(144), nullptr);
}

TEST(ReadTargetYaml, Checkerboard) {
  testing::TempDir dir;
  const CalibrationTarget target =
      ReadTargetYaml(dir.Write("cb.yaml",
                               "target_type: checkerboard\ntargetCols: 7\ntargetRows: 6\n"
                               "rowSpacingMeters: 0.06\ncolSpacingMeters: 0.05\n"));
  ASSERT_EQ(target.points.size(), 42u);
  EXPECT_NEAR((*target.Find(8) - Eigen::Vector3d(0.05, 0.06, 0.0)).norm(), 0.0, 1e-15);
}

TEST(ReadTargetYaml, PointsRoundTrip) {
  testing::TempDir dir;
  const CalibrationTarget target = ReadTargetYaml(dir.Write(
      "p.yaml",
      "target_type: points\npoints:\n  - [3, 0.1, 0.2, 0.0]\n  - [10, 0.5, -0.25, 0.125]\n"
      "  - [0, 0, 0, 0]\n  - [7, 1, 1, 1]\n"));
  EXPECT_EQ(target.points.size(), 4u);
  EXPECT_FALSE(target.IsPlanar());
  EXPECT_EQ(*target.Find(10), Eigen::Vector3d(0.5, -0.25, 0.125));
  const CalibrationTarget back =
      ReadTargetYaml(dir.Write("back.yaml", TargetPointsYamlText(target)));
  EXPECT_EQ(back.points, target.points);
}

TEST(ReadTargetYaml, RefusesBadFiles) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"target_type: circlegrid\n", "unsupported target_type 'circlegrid'"},
      {"target_type: aprilgrid\ntagCols: 0\ntagRows: 6\ntagSize: 0.1\ntagSpacing: 0.3\n",
       "tagCols"},
      {"target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: -0.1\ntagSpacing: 0.3\n",
       "tagSize"},
      {"target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.1\n", "tagSpacing"},
      {"target_type: aprilgrid\ntagCols: 30\ntagRows: 20\ntagSize: 0.1\ntagSpacing: 0.3\n",
       "bad.yaml:3: an aprilgrid of 30 x 20 tags needs more than the 587 codes"},
      {"target_type: checkerboard\ntargetCols: 2000\ntargetRows: 1000\nrowSpacingMeters: 0.1\n"
       "colSpacingMeters: 0.1\n",
       "bad.yaml:3: a checkerboard of 2000 x 1000 inner corners is beyond the plausible 1000000"},
      {"target_type: points\npoints:\n  - [1, 0, 0, 0]\n  - [1, 1, 0, 0]\n  - [2, 0, 1, 0]\n"
       "  - [3, 1, 1, 0]\n",
       "duplicate point id 1"},
      {"target_type: points\npoints:\n  - [1, 0, 0]\n", "expected [id, x, y, z]"},
      {"target_type: points\npoints:\n  - [-1, 0, 0, 0]\n", "integer >= 0"},
      {"target_type: points\npoints:\n  - [1, 0, 0, 0]\n", "at least 4 points"},
  };
  testing::ExpectEachFileRefused(
      cases, "bad.yaml", [](const std::string& path) { ReadTargetYaml(path); });
}

}  // namespace
}  // namespace splinecal
