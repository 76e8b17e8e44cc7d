#include "tag_code.h"

#include <bitset>
#include <cmath>
#include <vector>

#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
}

namespace splinecal {
namespace {

// Bilinear sample of `image` at (x, y), pixel centres at integers; false off the image.
bool Sample(const cv::Mat& image, const cv::Point2d& p, double* value) {
  const int x0 = static_cast<int>(std::floor(p.x)), y0 = static_cast<int>(std::floor(p.y));
  if (x0 < 0 || y0 < 0 || x0 + 1 >= image.cols || y0 + 1 >= image.rows) return false;
  const double fx = p.x - x0, fy = p.y - y0;
  const uint8_t* r0 = image.ptr<uint8_t>(y0);
  const uint8_t* r1 = image.ptr<uint8_t>(y0 + 1);
  *value = (1 - fy) * ((1 - fx) * r0[x0] + fx * r0[x0 + 1]) +
           fy * ((1 - fx) * r1[x0] + fx * r1[x0 + 1]);
  return true;
}

}  // namespace

int TagCodeErrors(const apriltag_family& family, const cv::Mat& image, const GridTag& tag,
                  double sharpening) {
  // Tag-local (x right, y up the printed grid, the black square [0, 1]^2) to image.
  std::vector<cv::Point2f> local, corners;
  for (int k = 0; k < 4; ++k) {
    local.emplace_back(static_cast<float>(kLocalX[k]), static_cast<float>(kLocalY[k]));
    corners.emplace_back(tag.corners[k]);
  }
  const cv::Mat H = cv::getPerspectiveTransform(local, corners);
  const auto to_image = [&H](double x, double y) {
    const double w = H.at<double>(2, 0) * x + H.at<double>(2, 1) * y + H.at<double>(2, 2);
    return cv::Point2d((H.at<double>(0, 0) * x + H.at<double>(0, 1) * y + H.at<double>(0, 2)) / w,
                       (H.at<double>(1, 0) * x + H.at<double>(1, 1) * y + H.at<double>(1, 2)) / w);
  };
  // libapriltag's cells: column cx, row cy of a width_at_border grid over the black square, row 0
  // at its tag-local y = +1 (corner p[0] of a detection is our corner 0, at libapriltag's
  // (-1, 1): aprilgrid_detector.cc), so cell (cx, cy) is centred at ((cx + 1/2) / n,
  // 1 - (cy + 1/2) / n).
  const int n = family.width_at_border;
  const auto cell = [&](int cx, int cy) {
    return to_image((cx + 0.5) / n, 1.0 - (cy + 0.5) / n);
  };
  std::vector<double> values(static_cast<size_t>(n) * n);
  double black = 0.0;
  int black_count = 0;
  const int border = (n - 6) / 2;  // tag36h11: a 6 x 6 data grid in the border
  for (int cy = 0; cy < n; ++cy) {
    for (int cx = 0; cx < n; ++cx) {
      double& v = values[static_cast<size_t>(cy) * n + cx];
      if (!Sample(image, cell(cx, cy), &v)) return -1;
      if (cx < border || cy < border || cx >= n - border || cy >= n - border) {
        black += v;
        ++black_count;
      }
    }
  }
  black /= black_count;
  // The white: the quiet zone and the gap beside each edge, 1.2 cells out, along the edge's
  // middle (its ends touch the small black squares between the tags).
  double white = 0.0;
  int white_count = 0;
  const double out = -1.2 / n;
  for (int i = border; i < n - border; ++i) {
    const double along = (i + 0.5) / n;
    for (const cv::Point2d& p : {to_image(along, out), to_image(along, 1.0 - out),
                                 to_image(out, along), to_image(1.0 - out, along)}) {
      double v = 0.0;
      if (!Sample(image, p, &v)) return -1;
      white += v;
      ++white_count;
    }
  }
  white /= white_count;
  if (!(white > black)) return -1;
  const double threshold = 0.5 * (black + white);
  uint64_t code = 0;
  for (uint32_t i = 0; i < family.nbits; ++i) {
    const int cx = static_cast<int>(family.bit_x[i]), cy = static_cast<int>(family.bit_y[i]);
    const auto at = [&](int x, int y) { return values[static_cast<size_t>(y) * n + x]; };
    const double laplacian = 4.0 * at(cx, cy) - at(cx - 1, cy) - at(cx + 1, cy) -
                             at(cx, cy - 1) - at(cx, cy + 1);
    code = (code << 1) | (at(cx, cy) + sharpening * laplacian > threshold ? 1u : 0u);
  }
  return static_cast<int>(std::bitset<64>(code ^ family.codes[tag.id]).count());
}

}  // namespace splinecal
