// PNG and JPEG decoding to 8-bit grey with libpng and libjpeg directly (private to src/detect/,
// behind detect/image_file.h). Both libraries print their complaints to stderr unless the caller
// installs its own handlers; these do, so that every problem becomes one splinecal::Error.
#ifndef SPLINECAL_SRC_DETECT_IMAGE_DECODERS_H_
#define SPLINECAL_SRC_DETECT_IMAGE_DECODERS_H_

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/detect/gray_image.h"

namespace splinecal {

// Larger images are refused before decoding, so that a corrupt header cannot ask for gigabytes:
// far beyond any calibration camera, small enough to allocate.
inline constexpr int64_t kMaxImagePixels = 100'000'000;

// Each throws splinecal::Error(path, 0, ...) naming the problem: a chunk that fails its CRC or a
// truncated file (PNG), corrupt or truncated data (JPEG), more than kMaxImagePixels, a format
// the decoder does not support.
GrayImage DecodePng(const std::vector<uint8_t>& bytes, const std::string& path);
GrayImage DecodeJpeg(const std::vector<uint8_t>& bytes, const std::string& path);

// The bytes of a PNG file of 8-bit pixels: grey (channels 1) or OpenCV's blue-green-red order
// (channels 3), rows `stride` bytes apart. Encoded with libpng rather than OpenCV's image codecs,
// whose library loads about 140 shared libraries at every start of a program linked with it
// (docs/reliability.md, "Process start"). Throws splinecal::Error on failure.
std::string EncodePng(const uint8_t* pixels, int width, int height, int channels,
                      std::ptrdiff_t stride);

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_IMAGE_DECODERS_H_
