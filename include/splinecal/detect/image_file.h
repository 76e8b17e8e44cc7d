// Reading and writing image files (PNG, JPEG) for detect/: the one place splinecal decodes
// pixels. libpng and libjpeg decode, with splinecal's own error handlers (by default both print
// to stderr and go on with made-up rows); OpenCV writes the overlays.
#ifndef SPLINECAL_DETECT_IMAGE_FILE_H_
#define SPLINECAL_DETECT_IMAGE_FILE_H_

#include <string>
#include <vector>

#include <Eigen/Core>

#include "splinecal/detect/gray_image.h"

namespace splinecal {

// Reads a PNG or JPEG file as 8-bit grey (colour weighted 0.299 R + 0.587 G + 0.114 B, 16-bit
// reduced to its high byte). Throws splinecal::Error(path, 0, ...) for a missing or unreadable
// file, a file over 1 GiB or that is not a PNG or JPEG, a truncated PNG (it ends before IEND) or
// one with a chunk failing its CRC, a damaged or truncated JPEG (libjpeg's "Corrupt JPEG data",
// "Premature end of JPEG file"), an image over 10^8 pixels (refused from its header, before
// decoding), and a format the decoders do not support.
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
