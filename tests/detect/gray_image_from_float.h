// The synthetic renderers' last step (render_aprilgrid.h, render_checkerboard.h): a float image
// of grey levels as the detector's 8-bit GrayImage. Header-only, test-only.
#ifndef SPLINECAL_TESTS_DETECT_GRAY_IMAGE_FROM_FLOAT_H_
#define SPLINECAL_TESTS_DETECT_GRAY_IMAGE_FROM_FLOAT_H_

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <opencv2/core.hpp>
#include <random>

#include "splinecal/detect/gray_image.h"

namespace splinecal {
namespace testing {

// Every pixel of `pixels` (CV_32F) plus Gaussian noise of std `noise` grey levels (none at 0;
// drawn row by row from a generator seeded with `seed`), rounded and clamped to 0..255.
inline GrayImage GrayImageFromFloat(const cv::Mat& pixels, double noise = 0.0, uint32_t seed = 0) {
  std::mt19937 rng(seed);
  std::normal_distribution<double> gauss(0.0, noise);
  GrayImage image;
  image.width = pixels.cols;
  image.height = pixels.rows;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height);
  for (int v = 0; v < image.height; ++v) {
    for (int u = 0; u < image.width; ++u) {
      const double value = pixels.at<float>(v, u) + (noise > 0 ? gauss(rng) : 0.0);
      image.pixels[static_cast<size_t>(v) * image.width + u] =
          static_cast<uint8_t>(std::clamp(std::lround(value), 0L, 255L));
    }
  }
  return image;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_DETECT_GRAY_IMAGE_FROM_FLOAT_H_
