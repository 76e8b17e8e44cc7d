// The checkerboard detector against exact truth: rendered boards (tests/detect/
// render_checkerboard.h) whose corner pixels are known, seen frontally, tilted and turned. Then on
// OpenCV's own sample stereo set (bundled in data/opencv_chessboard, byte-identical to
// ../shared/data/opencv_chessboard; 9 x 6 inner corners, 13 left and 13 right images): ids that
// agree between the two cameras, and the corners against OpenCV's findChessboardCorners +
// cornerSubPix as OpenCV's calibration test runs them (the same corner finder underneath, so that
// comparison checks the detector's wiring, not its accuracy: the rendered boards do that).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

#include "detect/render_checkerboard.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/detect/target_detector.h"
#include "testing/paths.h"

namespace splinecal {
namespace {

constexpr int kCols = 9, kRows = 6;
const int kImages[] = {1, 2, 3, 4, 5, 6, 7, 8, 9, 11, 12, 13, 14};  // 10 is absent

// data/opencv_chessboard/SOURCE.md: OpenCV's leftNN.jpg is cam0/<NN seconds in ns>.jpg, rightNN.jpg
// the same in cam1/.
std::string ImagePath(const std::string& side, int index) {
  return testing::BundledDataPath(std::string("opencv_chessboard/") +
                                  (side == "left" ? "cam0/" : "cam1/") + std::to_string(index) +
                                  "000000000.jpg");
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

// Rendered views: frontal, tilted by up to 50 degrees, turned in the image plane (a half turn
// included, which must not change the ids: corner 0 is the one inside a black square).
std::vector<testing::PinholeView> RenderedViews() {
  const auto rotation = [](double roll_deg, double pitch_deg, double yaw_deg) {
    const double k = M_PI / 180.0;
    return (Eigen::AngleAxisd(yaw_deg * k, Eigen::Vector3d::UnitZ()) *
            Eigen::AngleAxisd(pitch_deg * k, Eigen::Vector3d::UnitY()) *
            Eigen::AngleAxisd(roll_deg * k, Eigen::Vector3d::UnitX()))
        .toRotationMatrix();
  };
  std::vector<testing::PinholeView> views;
  // {roll, pitch, yaw [deg], board origin in the camera [m]}; the 9 x 6 board of 30 mm squares
  // spans 0.24 x 0.15 m between its outer corners, 200 to 300 px at these distances.
  const struct {
    double roll, pitch, yaw;
    Eigen::Vector3d t;
  } poses[] = {{0, 0, 0, {-0.12, -0.07, 0.55}},      {0, 35, 0, {-0.10, -0.08, 0.50}},
               {-30, 0, 20, {-0.14, -0.04, 0.60}},   {25, -40, -15, {-0.08, -0.06, 0.55}},
               {0, 0, 190, {0.12, 0.09, 0.55}},      {50, 10, 95, {0.05, -0.12, 0.60}},
               {-20, 45, 180, {0.13, 0.05, 0.65}}};
  for (const auto& p : poses) {
    testing::PinholeView view;
    view.R_cam_board = rotation(p.roll, p.pitch, p.yaw);
    view.t_cam_board = p.t;
    views.push_back(view);
  }
  return views;
}

// The detector's corners against the exact projections. Tolerance: 0.1 px. The renderer's own
// error is below 0.016 px (n-rooks sampling, 1/64 px steps; 8-bit rounding of 170 grey levels of
// contrast adds about 0.003 px). The rest is cornerSubPix's bias on sampled edges (it locks
// towards pixel positions): measured at most 0.056 px on the frontal view and 0.080 px over the
// tilted ones with a 1 px blur (0.03 to 0.06 px on the frontal view for blurs of 0.6 to 1.5 px).
// A half-pixel convention slip, a shifted or mirrored id (a whole square, ~27 px) fail it.
TEST(CheckerboardDetector, RenderedBoardsCornersWithinATenthOfAPixelOfTruth) {
  constexpr int kCols = 9, kRows = 6;
  const CalibrationTarget board = MakeCheckerboard(kCols, kRows, 0.03, 0.03);
  TargetDetector detector(board);
  double worst = 0;
  int view_index = 0;
  for (const testing::PinholeView& view : RenderedViews()) {
    SCOPED_TRACE("view " + std::to_string(view_index++));
    const GrayImage image = testing::RenderCheckerboard(board, view);
    const TargetDetection detection = detector.Detect(image.view());
    ASSERT_EQ(detection.corners.size(), static_cast<size_t>(kCols * kRows));
    for (const CornerDetection& corner : detection.corners) {
      const Eigen::Vector2d truth = view.Project(board.points.at(corner.point_id));
      const double error = (corner.uv - truth).norm();
      EXPECT_LT(error, 0.1) << "corner " << corner.point_id << " at " << corner.uv.transpose()
                             << ", true " << truth.transpose();
      worst = std::max(worst, error);
    }
  }
  std::printf("largest corner error on rendered boards: %.4f px\n", worst);
  RecordProperty("max_rendered_error_px", std::to_string(worst));
}

TEST(CheckerboardDetector, AllCornersOfEveryOpenCvSampleWithinFiveHundredthsOfOpenCv) {
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
  // 8 x 6 inner corners: OpenCV's finder does not report a 9 x 6 board as a smaller one.
  TargetDetector detector(MakeCheckerboard(8, 6, 1.0, 1.0));
  const GrayImage image = ReadGrayImage(ImagePath("left", 1));
  EXPECT_TRUE(detector.Detect(image.view()).corners.empty());
}

}  // namespace
}  // namespace splinecal
