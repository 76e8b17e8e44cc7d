// Borrowed OpenCV matrices over splinecal's image views (no copy). Private to src/detect/: the
// public headers carry no OpenCV type, so the library's users need no OpenCV headers.
#ifndef SPLINECAL_SRC_DETECT_OPENCV_VIEW_H_
#define SPLINECAL_SRC_DETECT_OPENCV_VIEW_H_

#include <opencv2/core.hpp>

#include "splinecal/detect/gray_image.h"
#include "splinecal/error.h"

namespace splinecal {

// The pixels of `image` as a CV_8UC1 matrix; throws splinecal::Error for an empty view or a
// stride below the width.
inline cv::Mat BorrowMat(const GrayImageView& image) {
  if (image.width <= 0 || image.height <= 0 || image.data == nullptr) {
    throw Error("image: empty (" + std::to_string(image.width) + " x " +
                std::to_string(image.height) + " pixels)");
  }
  if (image.stride < image.width) {
    throw Error("image: row stride " + std::to_string(image.stride) + " is below the width " +
                std::to_string(image.width));
  }
  return cv::Mat(image.height, image.width, CV_8UC1, const_cast<uint8_t*>(image.data),
                 static_cast<size_t>(image.stride));
}

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_OPENCV_VIEW_H_
