// The target-layout gate (camera/target_layout_check.h): the right layout passes on real EuRoC
// corners and on a 195-degree fisheye; a wrong column count or tagSpacing is refused with the
// layout the corners do fit.
#include "splinecal/camera/target_layout_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <filesystem>
#include <random>

#include "camera/camera_test_models.h"
#include "splinecal/error.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

std::string ErrorOf(const std::vector<Observation>& observations,
                    const CalibrationTarget& target) {
  try {
    CheckTargetLayout(observations, target, "observations.csv", "grid.yaml");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

// Views of `target` by `camera` from 12 poses (tilts up to about 30 degrees, the board centred
// `distance` in front), with Gaussian corner noise of noise_px: what a detector reports.
std::vector<Observation> SyntheticViews(const CalibrationTarget& target,
                                        const Camera& camera,
                                        double distance,
                                        double noise_px = 0.2) {
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const auto& [id, p] : target.points) centre += p / static_cast<double>(target.points.size());
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  std::vector<Observation> observations;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Matrix3d R =
        (Eigen::AngleAxisd(0.3 * k, Eigen::Vector3d::UnitZ()) *
         Eigen::AngleAxisd(0.5 * std::sin(k), Eigen::Vector3d::UnitX()) *
         Eigen::AngleAxisd(0.5 * std::cos(1.3 * k), Eigen::Vector3d::UnitY()))
            .toRotationMatrix();
    const Eigen::Vector3d t =
        Eigen::Vector3d(0.1 * std::sin(2.0 * k), 0.08 * std::cos(k), distance) - R * centre;
    for (const auto& [id, p] : target.points) {
      Eigen::Vector2d uv;
      if (!camera.Project(R * p + t, &uv) || !camera.InImage(uv)) continue;
      Observation o;
      o.t_ns = 1000000000LL + k * 50000000LL;
      o.point_id = id;
      const double du = noise_px * noise(rng);
      const double dv = noise_px * noise(rng);
      o.uv = uv + Eigen::Vector2d(du, dv);
      observations.push_back(o);
    }
  }
  return observations;
}

class EurocLayoutTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    const std::string path = testing::SharedDataPath("euroc_imu_april/observations.csv");
    if (std::filesystem::exists(path)) {
      observations_ = new std::vector<Observation>(ReadObservationsCsv(path));
    }
  }
  static void TearDownTestSuite() {
    delete observations_;
    observations_ = nullptr;
  }
  static std::vector<Observation>* observations_;
};
std::vector<Observation>* EurocLayoutTest::observations_ = nullptr;

TEST_F(EurocLayoutTest, TheRightGridFitsAndMeasuresItsSpacing) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const CalibrationTarget target =
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"));
  const GridLayoutFit fit =
      FitGridLayout(LayoutCheckFrames(*observations_, target), GridLayout{true, 12});
  // Measured: see docs/reliability.md. The bounds leave room for other detectors' noise.
  EXPECT_TRUE(fit.fits);
  EXPECT_GT(fit.samples, 1000);
  EXPECT_LT(fit.residual, 0.03);
  EXPECT_LT(fit.gross_fraction, 0.01);
  EXPECT_NEAR(fit.spacing, 0.3, 0.015);  // the printed board's ratio, with the lens's bias
  EXPECT_NEAR(fit.spacing_right, fit.spacing_up, 0.01);
  EXPECT_EQ(ErrorOf(*observations_, target), "");
}

TEST_F(EurocLayoutTest, EveryOtherColumnCountFails) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const std::vector<ObservationFrame> frames = LayoutCheckFrames(*observations_, target);
  for (int cols = 2; cols <= 144; ++cols) {
    for (const bool aprilgrid : {true, false}) {
      if (aprilgrid && cols % 2 != 0) continue;
      const GridLayoutFit fit = FitGridLayout(frames, GridLayout{aprilgrid, cols});
      EXPECT_EQ(fit.fits, aprilgrid && cols == 12)
          << (aprilgrid ? "aprilgrid " : "checkerboard ") << cols << " corners per row: median "
          << fit.residual << ", spacing " << fit.spacing_right << " / " << fit.spacing_up;
    }
  }
}

TEST_F(EurocLayoutTest, SevenBySevenGridIsRefusedNamingSixBySix) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const std::string error = ErrorOf(*observations_, MakeAprilGrid(7, 7, 0.088, 0.3));
  EXPECT_THAT(error,
              HasSubstr("observations.csv: the corners fit a 6 x 6 aprilgrid (tagCols x "
                        "tagRows) with tagSpacing 0.30, not the 7 x 7 aprilgrid (tagSpacing "
                        "0.30) of grid.yaml"));
  EXPECT_THAT(error, HasSubstr("fix tagCols/tagRows in grid.yaml"));
}

TEST_F(EurocLayoutTest, WrongSpacingRatioIsRefusedNamingTheMeasuredOne) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  for (const double wrong : {0.2, 0.25, 0.35}) {
    EXPECT_THAT(ErrorOf(*observations_, MakeAprilGrid(6, 6, 0.088, wrong)),
                HasSubstr("the corners fit tagSpacing 0.3"))
        << wrong;
  }
}

TEST_F(EurocLayoutTest, TallerGridThanTheBoardIsHarmlessAndPasses) {
  // A 6 x 8 file for the 6 x 6 board: the extra rows are never seen, the ids mean the same.
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  EXPECT_EQ(ErrorOf(*observations_, MakeAprilGrid(6, 8, 0.088, 0.3)), "");
}

// Lens independence: a 195-degree fisheye (TUM-VI's equidistant cam0) seeing the board from
// 0.35 m, corners up to about 60 degrees off axis.
TEST(TargetLayoutCheck, FisheyeViewsOfTheRightGridPass) {
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  const std::vector<Observation> observations =
      SyntheticViews(target, testing::TumViEquidistant(), 0.35);
  ASSERT_GT(observations.size(), 1000u);
  const GridLayoutFit fit =
      FitGridLayout(LayoutCheckFrames(observations, target), GridLayout{true, 12});
  EXPECT_TRUE(fit.fits);
  EXPECT_LT(fit.residual, 0.05);
  EXPECT_LT(fit.gross_fraction, 0.02);
  EXPECT_NEAR(fit.spacing, 0.3, 0.02);
  EXPECT_EQ(ErrorOf(observations, target), "");
  EXPECT_THAT(ErrorOf(observations, MakeAprilGrid(5, 7, 0.088, 0.3)),
              HasSubstr("the corners fit a 6 x 6 aprilgrid"));
}

TEST(TargetLayoutCheck, CheckerboardColumnsAreChecked) {
  const CalibrationTarget target = MakeCheckerboard(7, 6, 0.04, 0.04);
  const std::vector<Observation> observations =
      SyntheticViews(target, testing::EurocCamera(), 0.5);
  EXPECT_EQ(ErrorOf(observations, target), "");
  // Another square size or a different row spacing cannot be judged from pixels: passes.
  EXPECT_EQ(ErrorOf(observations, MakeCheckerboard(7, 6, 0.03, 0.05)), "");
  EXPECT_THAT(ErrorOf(observations, MakeCheckerboard(8, 6, 0.04, 0.04)),
              HasSubstr("the corners fit a 7 x 6 checkerboard (targetCols x targetRows), not "
                        "the 8 x 6 checkerboard of grid.yaml"));
}

TEST(TargetLayoutCheck, AnAprilgridFileForCheckerboardCornersIsRefused) {
  const std::vector<Observation> observations =
      SyntheticViews(MakeCheckerboard(8, 6, 0.04, 0.04), testing::EurocCamera(), 0.5);
  EXPECT_THAT(ErrorOf(observations, MakeAprilGrid(4, 3, 0.04, 0.3)),
              HasSubstr("the corners fit a 8 x 6 checkerboard"));
}

TEST(TargetLayoutCheck, TooLittleSeenIsNotJudged) {
  // One row of corners: no cell has a neighbour, nothing to judge (the calibration reports the
  // lack of corners itself).
  std::vector<Observation> observations;
  for (int id = 0; id < 8; ++id) {
    Observation o;
    o.point_id = id;
    o.uv = Eigen::Vector2d(300.0 + 20 * id, 200.0 + 10 * id);
    observations.push_back(o);
  }
  EXPECT_EQ(ErrorOf(observations, MakeAprilGrid(6, 6, 0.088, 0.3)), "");
  // A points target is never judged.
  CalibrationTarget points;
  points.type = "points";
  for (int id = 0; id < 8; ++id) points.points[id] = Eigen::Vector3d(id, 0.0, 0.0);
  EXPECT_EQ(ErrorOf(observations, points), "");
}

// The homography of a cell is exact for a pinhole without noise: every prediction lands on the
// grid to rounding (this pins the closed-form square-to-quad formula).
TEST(TargetLayoutCheck, PinholePredictionsAreExactWithoutNoise) {
  Camera pinhole = testing::EurocCamera();
  pinhole.distortion = DistortionModel::kNone;
  const CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.25);
  const std::vector<Observation> exact = SyntheticViews(target, pinhole, 0.6, 0.0);
  const GridLayoutFit fit = FitGridLayout(LayoutCheckFrames(exact, target), GridLayout{true, 12});
  EXPECT_LT(fit.residual, 1e-9);
  EXPECT_NEAR(fit.spacing, 0.25, 1e-9);
}

}  // namespace
}  // namespace splinecal
