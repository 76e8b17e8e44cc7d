#include "checkerboard_detector.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

namespace splinecal {
namespace {

// Mean intensity of the square whose corners are grid corners (r, c) to (r + 1, c + 1), sampled
// in a small patch around the square's centre.
double SquareIntensity(const cv::Mat& image,
                       const std::vector<cv::Point2f>& corners,
                       int cols,
                       int r,
                       int c) {
  const cv::Point2f centre = 0.25f * (corners[r * cols + c] + corners[r * cols + c + 1] +
                                      corners[(r + 1) * cols + c] + corners[(r + 1) * cols + c + 1]);
  const int x = std::clamp(static_cast<int>(std::lround(centre.x)), 1, image.cols - 2);
  const int y = std::clamp(static_cast<int>(std::lround(centre.y)), 1, image.rows - 2);
  return cv::mean(image(cv::Rect(x - 1, y - 1, 3, 3)))[0];
}

}  // namespace

TargetDetection DetectCheckerboard(const cv::Mat& image, const CalibrationTarget& target) {
  TargetDetection result;
  const int cols = target.grid_cols, rows = target.grid_rows;
  std::vector<cv::Point2f> corners;
  // FAST_CHECK rejects a frame without a board in a few milliseconds instead of a second.
  const int flags =
      cv::CALIB_CB_ADAPTIVE_THRESH | cv::CALIB_CB_NORMALIZE_IMAGE | cv::CALIB_CB_FAST_CHECK;
  if (!cv::findChessboardCorners(image, cv::Size(cols, rows), corners, flags) ||
      static_cast<int>(corners.size()) != cols * rows) {
    return result;
  }
  // OpenCV orders the corners row by row but may start at either end of the board. When
  // cols + rows is odd, the board is not symmetric under a half turn: the square inside corner 0
  // (between corners 0, 1, cols, cols + 1) and the one inside the last corner differ in colour.
  // Corner 0 is the one whose square is black, so the same physical corner gets the same id in
  // every camera and frame.
  if ((cols + rows) % 2 == 1) {
    const double first = SquareIntensity(image, corners, cols, 0, 0);
    const double last = SquareIntensity(image, corners, cols, rows - 2, cols - 2);
    if (first > last) std::reverse(corners.begin(), corners.end());
  }
  // Sub-pixel refinement with OpenCV's cornerSubPix (its gradient condition holds exactly at a
  // checkerboard's saddle): a half width of 5 px as OpenCV's own calibration samples use, less
  // when the squares are small, so that the window stays within the four squares around the
  // corner (0.4 of the shortest corner spacing, at least 2 px).
  double min_step = std::numeric_limits<double>::infinity();
  for (int r = 0; r < rows; ++r) {
    for (int c = 0; c < cols; ++c) {
      if (c + 1 < cols) min_step = std::min(min_step, cv::norm(corners[r * cols + c] - corners[r * cols + c + 1]));
      if (r + 1 < rows) min_step = std::min(min_step, cv::norm(corners[r * cols + c] - corners[(r + 1) * cols + c]));
    }
  }
  const int half = std::clamp(static_cast<int>(0.4 * min_step), 2, 5);
  cv::cornerSubPix(image, corners, cv::Size(half, half), cv::Size(-1, -1),
                   cv::TermCriteria(cv::TermCriteria::EPS + cv::TermCriteria::COUNT, 30, 0.001));
  for (int i = 0; i < cols * rows; ++i) {
    result.corners.push_back({i, Eigen::Vector2d(corners[i].x, corners[i].y)});
  }
  return result;
}

}  // namespace splinecal
