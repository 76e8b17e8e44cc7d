// The image-size gate (camera/image_bounds_check.h) on EuRoC imu_april's real corners (752 x 480
// cameras): the right size passes, 640 x 480 is refused with the count, the largest pixel and a
// size that fits.
#include "splinecal/camera/image_bounds_check.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/io/observations_csv.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

Camera Sized(int width, int height) {
  Camera camera;
  camera.width = width;
  camera.height = height;
  return camera;
}

std::string ErrorOf(const std::vector<Observation>& observations,
                    const std::vector<Camera>& cameras) {
  try {
    CheckCornersInsideImages(observations, cameras, "observations.csv", "--resolution");
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(ImageBoundsCheck, EurocCornersFitTheirImageAndNotVga) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const std::vector<Observation> observations =
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv"));
  const std::vector<ImageBoundsSummary> right =
      SummariseImageBounds(observations, {Sized(752, 480), Sized(752, 480)});
  // SOURCE.md: 179,524 corners of cam0.
  EXPECT_EQ(right[0].corners, 179524);
  EXPECT_EQ(right[0].outside, 0);
  EXPECT_EQ(right[1].outside, 0);
  EXPECT_EQ(ErrorOf(observations, {Sized(752, 480), Sized(752, 480)}), "");
  // The largest u, v (747.7, 476.3: awk over the file) need at least 749 x 477.
  EXPECT_EQ(right[0].smallest_fitting_size, Eigen::Vector2i(749, 477));

  const std::string error = ErrorOf(observations, {Sized(640, 480), Sized(752, 480)});
  EXPECT_THAT(error,
              HasSubstr("observations.csv: cam0: 2083 of 179524 corners lie outside its 640 x "
                        "480 image from --resolution (largest u 747.7, v 476.3); the image is "
                        "at least 749 x 477 (e.g. 752 x 480): fix the size in --resolution"));
}

TEST(ImageBoundsCheck, TheBorderIsThePixelConventionsWithinTolerance) {
  // Pixel centres at integers: a 10 x 10 image spans [-0.5, 9.5]; one pixel of tolerance.
  std::vector<Observation> observations(2);
  observations[0].uv = Eigen::Vector2d(-1.4, 10.4);
  observations[1].uv = Eigen::Vector2d(10.4, -1.4);
  EXPECT_EQ(ErrorOf(observations, {Sized(10, 10)}), "");
  observations[1].uv.x() = 10.6;
  EXPECT_THAT(ErrorOf(observations, {Sized(10, 10)}), HasSubstr("1 of 2 corners lie outside"));
  observations[1].uv = Eigen::Vector2d(5.0, -1.6);
  EXPECT_THAT(ErrorOf(observations, {Sized(10, 10)}), HasSubstr("corners at negative u or v"));
  // Unknown size (0): not checked.
  EXPECT_EQ(ErrorOf(observations, {Sized(0, 0)}), "");
}

}  // namespace
}  // namespace splinecal
