// Test images of a Kalibr AprilGrid seen by a camera, with known corner positions: the grid's
// texture drawn from tag36h11's codes, mapped into a distorted camera image through the plane's
// homography, 3 x 3 sub-pixels per pixel, a lens blur, noise and 8-bit rounding. For tests that
// chain `detect` with what comes after it (tests/detect/detect_calibrate_test.cc).
#ifndef SPLINECAL_TESTS_DETECT_RENDER_APRILGRID_H_
#define SPLINECAL_TESTS_DETECT_RENDER_APRILGRID_H_

#include <cmath>
#include <random>
#include <vector>

#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>

extern "C" {
#include <apriltag/apriltag.h>
#include <apriltag/tag36h11.h>
}

#include "detect/gray_image_from_float.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"
#include "splinecal/detect/gray_image.h"

namespace splinecal {
namespace testing {

// The grid on the target plane: white paper, for each tag a black square of 10 x 10 bits (a
// 2-bit border around tag36h11's 6 x 6 code, white bits where the code has a 1) and a black
// square of the gap's size at every tag corner, the grid's outer corners included. Tag k sits at
// column k mod cols, row k / cols, its code upright when the target's y axis points up.
class AprilGridTexture {
 public:
  AprilGridTexture(const CalibrationTarget& target, int pixels_per_bit) : target_(target) {
    apriltag_family_t* family = tag36h11_create();
    for (int id = 0; id < target.grid_cols * target.grid_rows; ++id) {
      // apriltag_to_image: 10 x 10, a white ring, the 1-bit black border, the code inside.
      image_u8_t* tag = apriltag_to_image(family, id);
      std::vector<uint8_t> bits(100);
      for (int r = 0; r < 10; ++r) {
        for (int c = 0; c < 10; ++c) bits[r * 10 + c] = tag->buf[r * tag->stride + c];
      }
      codes_.push_back(bits);
      image_u8_destroy(tag);
    }
    tag36h11_destroy(family);
    const double size = target.tag_size_m, gap = target.tag_spacing_ratio * size;
    metres_per_pixel_ = size / 10.0 / pixels_per_bit;
    x0_ = y0_ = -gap - size;  // a margin of a tag around the outer squares
    const double width = target.grid_cols * (size + gap) + gap + 2 * size;
    const double height = target.grid_rows * (size + gap) + gap + 2 * size;
    texture_ = cv::Mat(static_cast<int>(height / metres_per_pixel_),
                       static_cast<int>(width / metres_per_pixel_), CV_32F);
    for (int j = 0; j < texture_.rows; ++j) {
      for (int i = 0; i < texture_.cols; ++i) {
        const Eigen::Vector2d p = PlaneOfTexel(i, j);
        texture_.at<float>(j, i) = Intensity(p.x(), p.y());
      }
    }
  }

  // The target-plane point [m] at the centre of texture pixel (i, j); row 0 is the top (max y).
  Eigen::Vector2d PlaneOfTexel(double i, double j) const {
    return {x0_ + (i + 0.5) * metres_per_pixel_, y0_ + (texture_.rows - 0.5 - j) * metres_per_pixel_};
  }
  // The inverse: texture pixel coordinates of a plane point.
  Eigen::Vector2d TexelOfPlane(double x, double y) const {
    return {(x - x0_) / metres_per_pixel_ - 0.5, texture_.rows - 0.5 - (y - y0_) / metres_per_pixel_};
  }
  const cv::Mat& texture() const { return texture_; }

 private:
  float Intensity(double x, double y) const {
    const double size = target_.tag_size_m, gap = target_.tag_spacing_ratio * size;
    const double pitch = size + gap;
    // The small squares: [c pitch - gap, c pitch) x [r pitch - gap, r pitch), c, r = 0..n.
    const int sc = static_cast<int>(std::floor((x + gap) / pitch));
    const int sr = static_cast<int>(std::floor((y + gap) / pitch));
    if (sc >= 0 && sc <= target_.grid_cols && sr >= 0 && sr <= target_.grid_rows &&
        x + gap - sc * pitch < gap && y + gap - sr * pitch < gap) {
      return 0.0f;
    }
    const int c = static_cast<int>(std::floor(x / pitch));
    const int r = static_cast<int>(std::floor(y / pitch));
    if (c < 0 || r < 0 || c >= target_.grid_cols || r >= target_.grid_rows) return 255.0f;
    const double fx = x - c * pitch, fy = y - r * pitch;
    if (fx >= size || fy >= size) return 255.0f;
    const int bx = static_cast<int>(fx / (size / 10.0));
    const int by = static_cast<int>(fy / (size / 10.0));  // from the tag's bottom
    if (bx < 2 || bx > 7 || by < 2 || by > 7) return 0.0f;  // the 2-bit border
    // Code bit rows count from the tag's top; columns from its left.
    return codes_[r * target_.grid_cols + c][(9 - by) * 10 + bx] > 127 ? 255.0f : 0.0f;
  }

  CalibrationTarget target_;
  std::vector<std::vector<uint8_t>> codes_;
  double metres_per_pixel_ = 0, x0_ = 0, y0_ = 0;
  cv::Mat texture_;
};

// Renders frames of one camera: rays of every sub-pixel computed once, then per frame the
// homography from the target plane to the rays (fitted to the frame's exact corner pixels).
class PlanarViewRenderer {
 public:
  static constexpr int kSub = 3;  // sub-pixels per pixel and axis

  PlanarViewRenderer(const Camera& camera, const AprilGridTexture& texture)
      : camera_(camera), texture_(texture) {
    rays_ = cv::Mat(camera.height * kSub, camera.width * kSub, CV_32FC2);
    for (int y = 0; y < rays_.rows; ++y) {
      for (int x = 0; x < rays_.cols; ++x) {
        const Eigen::Vector2d uv((x + 0.5) / kSub - 0.5, (y + 0.5) / kSub - 0.5);
        Eigen::Vector3d ray(1e6, 1e6, 1.0);  // far off the target where Unproject fails
        camera.Unproject(uv, &ray);
        rays_.at<cv::Vec2f>(y, x) = cv::Vec2f(static_cast<float>(ray.x()), static_cast<float>(ray.y()));
      }
    }
  }

  // The image of the frame whose exact corner pixels are `corners` (ids of `target`), with a
  // lens blur of `blur_px` and Gaussian noise of `noise` grey levels.
  GrayImage Render(const std::vector<Observation>& corners, const CalibrationTarget& target,
                   double blur_px, double noise, uint32_t seed) const {
    std::vector<cv::Point2d> plane, rays;
    for (const Observation& o : corners) {
      Eigen::Vector3d ray;
      if (!camera_.Unproject(o.uv, &ray)) continue;
      const Eigen::Vector3d& p = target.points.at(o.point_id);
      plane.emplace_back(p.x(), p.y());
      rays.emplace_back(ray.x(), ray.y());
    }
    const cv::Mat H = cv::findHomography(rays, plane, 0);  // ray (x, y, 1) -> plane
    cv::Mat map(rays_.size(), CV_32FC2);
    for (int y = 0; y < rays_.rows; ++y) {
      for (int x = 0; x < rays_.cols; ++x) {
        const cv::Vec2f r = rays_.at<cv::Vec2f>(y, x);
        const double w = H.at<double>(2, 0) * r[0] + H.at<double>(2, 1) * r[1] + H.at<double>(2, 2);
        const double px = (H.at<double>(0, 0) * r[0] + H.at<double>(0, 1) * r[1] + H.at<double>(0, 2)) / w;
        const double py = (H.at<double>(1, 0) * r[0] + H.at<double>(1, 1) * r[1] + H.at<double>(1, 2)) / w;
        const Eigen::Vector2d t = texture_.TexelOfPlane(px, py);
        map.at<cv::Vec2f>(y, x) = cv::Vec2f(static_cast<float>(t.x()), static_cast<float>(t.y()));
      }
    }
    cv::Mat fine, pixels;
    cv::remap(texture_.texture(), fine, map, cv::noArray(), cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(120));
    if (blur_px > 0) cv::GaussianBlur(fine, fine, cv::Size(0, 0), blur_px * kSub);
    cv::resize(fine, pixels, cv::Size(camera_.width, camera_.height), 0, 0, cv::INTER_AREA);
    return GrayImageFromFloat(pixels, noise, seed);
  }

 private:
  Camera camera_;
  const AprilGridTexture& texture_;
  cv::Mat rays_;
};

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_DETECT_RENDER_APRILGRID_H_
