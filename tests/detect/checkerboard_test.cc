// The checkerboard detector on OpenCV's own sample stereo set (../shared/data/opencv_chessboard,
// 9 x 6 inner corners, 13 left and 13 right images), against OpenCV's findChessboardCorners +
// cornerSubPix as OpenCV's calibration test runs them.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

constexpr int kCols = 9, kRows = 6;
const int kImages[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14};  // 10 is absent

std::string ImagePath(const std::string& side, int index) {
  char name[32];
  std::snprintf(name, sizeof(name), "%s%02d.jpg", side.c_str(), index);
  return testing::SharedDataPath(std::string("opencv_chessboard/") + name);
}

// OpenCV's reference: default flags, then cornerSubPix with winSize (5, 5) (an 11 x 11 window),
// zeroZone none, 30 iterations or 0.001 px (the criteria of OpenCV's calibration test).
std::vector<cv::Point2f> OpenCvCorners(const GrayImage& image) {
  cv::Mat pixels(image.height, image.width, CV_8UC1, const_cast<uint8_t*>(image.pixels.data()));
  std::vector<cv::Point2f> corners;
  EXPECT_TRUE(cv::findChessboardCorners(pixels, cv::Size(kCols, kRows), corners));
  cv::cornerSubPix(pixels, corners, cv::Size(5, 5), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  return corners;
}

// The largest distance between our corners and OpenCV's, matched as OpenCV orders them or in
// the reverse order (our ids fix corner 0 by its square's colour; OpenCV may start at either
// end). Sets `reversed` to the order that matched.
double MaxDistance(const TargetDetection& ours, const std::vector<cv::Point2f>& reference,
                   bool* reversed) {
  double forward = 0, backward = 0;
  const int n = static_cast<int>(reference.size());
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector2d f(reference[i].x, reference[i].y);
    const Eigen::Vector2d b(reference[n - 1 - i].x, reference[n - 1 - i].y);
    forward = std::max(forward, (ours.corners[i].uv - f).norm());
    backward = std::max(backward, (ours.corners[i].uv - b).norm());
  }
  *reversed = backward < forward;
  return std::min(forward, backward);
}

TEST(CheckerboardDetector, AllCornersOfEveryOpenCvSampleWithinFiveHundredthsOfOpenCv) {
  SPLINECAL_REQUIRE_SHARED_DATA("opencv_chessboard");
  const CalibrationTarget board = MakeCheckerboard(kCols, kRows, 1.0, 1.0);
  TargetDetector detector(board);
  double worst = 0;
  for (const std::string side : {"left", "right"}) {
    for (int index : kImages) {
      SCOPED_TRACE(ImagePath(side, index));
      const GrayImage image = ReadGrayImage(ImagePath(side, index));
      const TargetDetection detection = detector.Detect(image.view());
      ASSERT_EQ(detection.corners.size(), static_cast<size_t>(kCols * kRows));
      for (int i = 0; i < kCols * kRows; ++i) EXPECT_EQ(detection.corners[i].point_id, i);
      bool reversed = false;
      const double distance = MaxDistance(detection, OpenCvCorners(image), &reversed);
      EXPECT_LT(distance, 0.05);
      worst = std::max(worst, distance);
    }
  }
  RecordProperty("max_distance_px", std::to_string(worst));
}

// A stereo pair sees the board from nearly the same direction: the same id must be the same
// physical corner, so the direction from corner 0 to the last corner agrees between the two
// images, and the square inside corner 0 is black in both.
TEST(CheckerboardDetector, IdsAgreeBetweenLeftAndRightImages) {
  SPLINECAL_REQUIRE_SHARED_DATA("opencv_chessboard");
  const CalibrationTarget board = MakeCheckerboard(kCols, kRows, 1.0, 1.0);
  TargetDetector detector(board);
  for (int index : kImages) {
    SCOPED_TRACE(index);
    Eigen::Vector2d direction[2];
    int k = 0;
    for (const std::string side : {"left", "right"}) {
      const GrayImage image = ReadGrayImage(ImagePath(side, index));
      const TargetDetection d = detector.Detect(image.view());
      ASSERT_EQ(d.corners.size(), static_cast<size_t>(kCols * kRows));
      direction[k++] = (d.corners.back().uv - d.corners.front().uv).normalized();
      // Inside corner 0: between corners 0, 1, cols, cols + 1.
      const Eigen::Vector2d centre = 0.25 * (d.corners[0].uv + d.corners[1].uv +
                                             d.corners[kCols].uv + d.corners[kCols + 1].uv);
      const Eigen::Vector2d next = 0.25 * (d.corners[1].uv + d.corners[2].uv +
                                           d.corners[kCols + 1].uv + d.corners[kCols + 2].uv);
      const auto at = [&](const Eigen::Vector2d& p) {
        return image.pixels[static_cast<size_t>(std::lround(p.y())) * image.width +
                            std::lround(p.x())];
      };
      EXPECT_LT(at(centre) + 40, at(next)) << side << ": corner 0's square is not the dark one";
    }
    EXPECT_GT(direction[0].dot(direction[1]), std::cos(20.0 * M_PI / 180.0));
  }
}

TEST(CheckerboardDetector, ABoardWithOtherCountsIsNotFound) {
  SPLINECAL_REQUIRE_SHARED_DATA("opencv_chessboard");
  // 8 x 6 inner corners: OpenCV's finder does not report a 9 x 6 board as a smaller one.
  TargetDetector detector(MakeCheckerboard(8, 6, 1.0, 1.0));
  const GrayImage image = ReadGrayImage(ImagePath("left", 1));
  EXPECT_TRUE(detector.Detect(image.view()).corners.empty());
}

}  // namespace
}  // namespace splinecal
