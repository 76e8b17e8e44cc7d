// Resampled copies of a real frame for recall tests of the AprilGrid detector: the frame as a
// picture on a plane, turned by up to 60 degrees about the grid's centre, seen by a pinhole
// camera, scaled down, then blurred and noisy. Every pixel of a copy is the mean of 3 x 3 samples
// (a camera integrates over its pixel; point sampling would alias the scaled-down code bits).
// Truth: a corner at x in the frame is at H x in the copy, H the homography that made it.
#ifndef SPLINECAL_TESTS_DETECT_WARPED_VIEWS_H_
#define SPLINECAL_TESTS_DETECT_WARPED_VIEWS_H_

#include <algorithm>
#include <cmath>
#include <map>
#include <random>
#include <vector>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <opencv2/core.hpp>
#include <opencv2/core/eigen.hpp>
#include <opencv2/imgproc.hpp>

#include "splinecal/detect/gray_image.h"

namespace splinecal {
namespace testing {

struct ViewSpec {
  double scale = 1.0;     // of the grid's centre, along the tilt axis
  double tilt_deg = 0.0;  // the plane turned about an axis in it through the grid's centre
  double tilt_axis_deg = 0.0;  // that axis' direction in the frame (0 = the u axis)
  double roll_deg = 0.0;  // then turned in the image
  double blur_px = 0.0;   // Gaussian lens blur, sigma in the copy's pixels
  double noise = 0.0;     // Gaussian noise, std in grey levels
  uint32_t seed = 1;
};

struct WarpedView {
  GrayImage image;
  Eigen::Matrix3d H;  // frame pixel (centres at integers) -> copy pixel
};

inline Eigen::Vector2d Apply(const Eigen::Matrix3d& H, const Eigen::Vector2d& x) {
  return (H * x.homogeneous()).hnormalized();
}

// The copy of `frame` for `spec`, framed on `region` (frame pixels that must be in view, e.g.
// the grid's corners) with a margin of a quarter of its size.
inline WarpedView MakeWarpedView(const GrayImageView& frame, const std::vector<Eigen::Vector2d>& region,
                                 const ViewSpec& spec) {
  Eigen::Vector2d centre = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : region) centre += p / static_cast<double>(region.size());
  // The plane at depth 1 facing a camera of focal length f (0.6 of the frame's width, EuRoC's
  // 458 px at 752), turned about the axis, seen by the same camera: H = K [r1 r2 t] K^-1.
  const double f = 0.6 * frame.width;
  const double axis = spec.tilt_axis_deg * M_PI / 180.0;
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(spec.tilt_deg * M_PI / 180.0,
                        Eigen::Vector3d(std::cos(axis), std::sin(axis), 0.0))
          .toRotationMatrix();
  Eigen::Matrix3d plane_to_camera;
  plane_to_camera << R.col(0), R.col(1), Eigen::Vector3d(0, 0, 1);
  Eigen::Matrix3d to_plane;  // frame pixel -> plane point (x, y, 1) at depth 1
  to_plane << 1 / f, 0, -centre.x() / f, 0, 1 / f, -centre.y() / f, 0, 0, 1;
  const double roll = spec.roll_deg * M_PI / 180.0;
  Eigen::Matrix3d to_pixels;  // camera ray -> copy pixel, before framing
  to_pixels << spec.scale * f * std::cos(roll), -spec.scale * f * std::sin(roll), 0,
      spec.scale * f * std::sin(roll), spec.scale * f * std::cos(roll), 0, 0, 0, 1;
  Eigen::Matrix3d H = to_pixels * plane_to_camera * to_plane;
  // Frame the region with a margin.
  Eigen::Vector2d low(1e300, 1e300), high(-1e300, -1e300);
  for (const Eigen::Vector2d& p : region) {
    const Eigen::Vector2d q = Apply(H, p);
    low = low.cwiseMin(q);
    high = high.cwiseMax(q);
  }
  const Eigen::Vector2d margin = 0.25 * (high - low) + Eigen::Vector2d(16, 16);
  low -= margin;
  high += margin;
  Eigen::Matrix3d shift = Eigen::Matrix3d::Identity();
  shift(0, 2) = -std::floor(low.x());
  shift(1, 2) = -std::floor(low.y());
  H = shift * H;
  const int width = static_cast<int>(std::ceil(high.x() - std::floor(low.x())));
  const int height = static_cast<int>(std::ceil(high.y() - std::floor(low.y())));
  // Sample at 3 x 3 points per copy pixel: sub-sample (i, j) of pixel (u, v) is at
  // 3 (u + 1/2) - 1/2 + (i - 1) on the fine grid, i.e. the fine grid is A = 3 (x + 1/2) - 1/2.
  constexpr int kSub = 3;
  Eigen::Matrix3d A;
  A << kSub, 0, (kSub - 1) / 2.0, 0, kSub, (kSub - 1) / 2.0, 0, 0, 1;
  const Eigen::Matrix3d fine_H = A * H;
  cv::Mat H_cv;
  cv::eigen2cv(fine_H, H_cv);
  const cv::Mat source(frame.height, frame.width, CV_8UC1, const_cast<uint8_t*>(frame.data),
                       static_cast<size_t>(frame.stride));
  cv::Mat source_f, fine, pixels;
  source.convertTo(source_f, CV_32F);
  cv::warpPerspective(source_f, fine, H_cv, cv::Size(width * kSub, height * kSub), cv::INTER_LINEAR,
                      cv::BORDER_REPLICATE);
  cv::resize(fine, pixels, cv::Size(width, height), 0, 0, cv::INTER_AREA);
  if (spec.blur_px > 0) cv::GaussianBlur(pixels, pixels, cv::Size(0, 0), spec.blur_px);
  std::mt19937 rng(spec.seed);
  std::normal_distribution<double> gauss(0.0, spec.noise);
  WarpedView view;
  view.H = H;
  view.image.width = width;
  view.image.height = height;
  view.image.pixels.resize(static_cast<size_t>(width) * height);
  for (int v = 0; v < height; ++v) {
    for (int u = 0; u < width; ++u) {
      const double value = pixels.at<float>(v, u) + (spec.noise > 0 ? gauss(rng) : 0.0);
      view.image.pixels[static_cast<size_t>(v) * width + u] =
          static_cast<uint8_t>(std::clamp(std::lround(value), 0L, 255L));
    }
  }
  return view;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_DETECT_WARPED_VIEWS_H_
