// Reading and writing image files (PNG, JPEG) for detect/: the one place splinecal decodes
// pixels. libjpeg decodes JPEGs (so that corrupt data is an error, not a printed warning and a
// grey image), OpenCV's codecs the rest, after the checks they lack.
#ifndef SPLINECAL_DETECT_IMAGE_FILE_H_
#define SPLINECAL_DETECT_IMAGE_FILE_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "splinecal/detect/gray_image.h"

namespace splinecal {

// Reads a PNG or JPEG file as 8-bit grey (colour is converted, 16-bit scaled down). Throws
// splinecal::Error(path, 0, ...) for a missing or unreadable file, a file that is not an image, a
// truncated one (a PNG that ends before its IEND chunk, a JPEG without its end-of-image marker:
// decoders fill the missing rows with grey and go on, which would give corners in made-up
// pixels), a PNG chunk that fails its CRC, corrupt JPEG data, and data a decoder refuses.
GrayImage ReadGrayImage(const std::string& path);

// A detection drawn over its image, for people to check (`detect --draw`): each corner as a
// circle with its id beside it. Writes a PNG; throws splinecal::Error when it cannot.
struct OverlayCorner {
  long long id = 0;
  Eigen::Vector2d uv = Eigen::Vector2d::Zero();
};
void WriteOverlayPng(const GrayImageView& image,
                     const std::vector<OverlayCorner>& corners,
                     const std::string& caption,
                     const std::string& path);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_IMAGE_FILE_H_
