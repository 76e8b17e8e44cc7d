// 8-bit greyscale images, the input of the corner detectors (detect/target_detector.h).
//
// GrayImageView borrows pixels (a decoded file, a numpy array, a camera driver's buffer) without
// copying them; GrayImage owns its pixels. Pixel (u, v) is column u, row v, at data[v stride + u];
// pixel centres are at integer coordinates (docs/conventions.md, "Cameras").
#ifndef SPLINECAL_DETECT_GRAY_IMAGE_H_
#define SPLINECAL_DETECT_GRAY_IMAGE_H_

#include <cstddef>
#include <cstdint>
#include <vector>

namespace splinecal {

struct GrayImageView {
  int width = 0;
  int height = 0;
  std::ptrdiff_t stride = 0;  // bytes from one row to the next (>= width)
  const uint8_t* data = nullptr;
};

struct GrayImage {
  int width = 0;
  int height = 0;
  std::vector<uint8_t> pixels;  // row-major, width * height

  GrayImageView view() const { return {width, height, width, pixels.data()}; }
};

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_GRAY_IMAGE_H_
