// Test images of a checkerboard whose corner pixels are known exactly: a pinhole camera (no
// distortion) looks at the board plane; each pixel is the mean of the board's black and white
// squares over the pixel's area (the box filter of a sensor pixel), then the image is blurred by
// a Gaussian lens blur and rounded to 8 bits. The true corner is the plane point's projection, in
// the detector's convention of pixel centres at integer coordinates (detect/target_detector.h).
//
// The pixel's mean comes from n^2 samples placed as n-rooks (every sample in a column and a row
// of its own of an n^2 x n^2 sub-grid): an edge parallel to an image axis, the worst case, then
// moves the mean in steps of 1/n^2 px, where an n x n grid would quantise it to 1/n px (4 x 4:
// corners off by up to 0.125 px, measured). Box filter and blur keep the corner exact: near a
// corner the pattern is two straight edges crossing, symmetric under a half turn about the
// corner, and so is its image under any symmetric filter, whose saddle stays at the corner.
// Without blur (a lens sharper than a pixel) the corner finder locks towards pixel positions by
// up to 0.15 px (measured); real lenses blur by about a pixel.
#ifndef SPLINECAL_TESTS_DETECT_RENDER_CHECKERBOARD_H_
#define SPLINECAL_TESTS_DETECT_RENDER_CHECKERBOARD_H_

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdint>
#include <opencv2/imgproc.hpp>
#include <vector>

#include "detect/gray_image_from_float.h"
#include "splinecal/camera/target.h"
#include "splinecal/detect/gray_image.h"

namespace splinecal {
namespace testing {

struct PinholeView {
  double f = 500.0;  // focal length [px], both axes
  double cx = 319.5, cy = 239.5;
  int width = 640, height = 480;
  Eigen::Matrix3d R_cam_board = Eigen::Matrix3d::Identity();
  Eigen::Vector3d t_cam_board = Eigen::Vector3d(0, 0, 1);  // board origin in the camera [m]

  Eigen::Vector2d Project(const Eigen::Vector3d& p_board) const {
    const Eigen::Vector3d p = R_cam_board * p_board + t_cam_board;
    return {f * p.x() / p.z() + cx, f * p.y() / p.z() + cy};
  }
};

// The board of `target` (MakeCheckerboard: inner corner (c, r) at (c dx, r dy, 0)): squares from
// one spacing before the first corner to one after the last, the square between corners 0, 1,
// cols and cols + 1 black (the detector's id convention), a white margin of `margin_squares`
// squares around it, grey (128) beyond. Intensities: black 40, white 210.
// blur_px: the lens blur's standard deviation [px].
inline GrayImage RenderCheckerboard(const CalibrationTarget& target, const PinholeView& view,
                                    double blur_px = 1.0, int samples_per_axis = 8,
                                    double margin_squares = 1.5) {
  const double dx = target.points.at(1).x();
  const double dy = target.points.at(target.grid_cols).y();
  // Image point (u, v, 1) -> board plane (x, y, 1): the inverse of the plane's homography
  // K [r1 r2 t].
  Eigen::Matrix3d K;
  K << view.f, 0, view.cx, 0, view.f, view.cy, 0, 0, 1;
  Eigen::Matrix3d H;
  H << view.R_cam_board.col(0), view.R_cam_board.col(1), view.t_cam_board;
  const Eigen::Matrix3d image_to_board = (K * H).inverse();
  const auto intensity = [&](double u, double v) {
    const Eigen::Vector3d q = image_to_board * Eigen::Vector3d(u, v, 1.0);
    if (q.z() <= 0) return 128.0;  // behind the camera
    const double x = q.x() / q.z() / dx, y = q.y() / q.z() / dy;  // in squares
    const double lo_x = -1.0, hi_x = target.grid_cols, lo_y = -1.0, hi_y = target.grid_rows;
    if (x < lo_x - margin_squares || x >= hi_x + margin_squares || y < lo_y - margin_squares ||
        y >= hi_y + margin_squares) {
      return 128.0;
    }
    if (x < lo_x || x >= hi_x || y < lo_y || y >= hi_y) return 210.0;
    const long i = static_cast<long>(std::floor(x)), j = static_cast<long>(std::floor(y));
    return (i + j) % 2 == 0 ? 40.0 : 210.0;
  };
  const int n = samples_per_axis, n2 = n * n;
  cv::Mat pixels(view.height, view.width, CV_32F);
  for (int v = 0; v < view.height; ++v) {
    for (int u = 0; u < view.width; ++u) {
      double sum = 0;
      for (int a = 0; a < n; ++a) {
        for (int b = 0; b < n; ++b) {
          // n-rooks: sub-column a n + b, sub-row b n + a.
          sum += intensity(u - 0.5 + (a * n + b + 0.5) / n2, v - 0.5 + (b * n + a + 0.5) / n2);
        }
      }
      pixels.at<float>(v, u) = static_cast<float>(sum / n2);
    }
  }
  if (blur_px > 0) cv::GaussianBlur(pixels, pixels, cv::Size(0, 0), blur_px);
  // Intensities 40..210 averaged: the clamp to 0..255 never acts.
  return GrayImageFromFloat(pixels);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_DETECT_RENDER_CHECKERBOARD_H_
