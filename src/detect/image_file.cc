#include "splinecal/detect/image_file.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "opencv_view.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

bool StartsWith(const std::vector<uint8_t>& bytes, std::initializer_list<uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

// A PNG ends with its IEND chunk: length 0, "IEND", CRC AE 42 60 82.
bool PngIsComplete(const std::vector<uint8_t>& bytes) {
  static const uint8_t kIend[12] = {0, 0, 0, 0, 'I', 'E', 'N', 'D', 0xAE, 0x42, 0x60, 0x82};
  return bytes.size() >= 12 && std::equal(kIend, kIend + 12, bytes.end() - 12);
}

// A JPEG ends with the end-of-image marker FF D9 (some writers pad a few bytes after it).
bool JpegIsComplete(const std::vector<uint8_t>& bytes) {
  const size_t tail = std::min<size_t>(bytes.size(), 64);
  for (size_t i = bytes.size() - tail; i + 1 < bytes.size(); ++i) {
    if (bytes[i] == 0xFF && bytes[i + 1] == 0xD9) return true;
  }
  return false;
}

}  // namespace

GrayImage ReadGrayImage(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open the image");
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                                   std::istreambuf_iterator<char>());
  if (in.bad()) throw Error(path, 0, "cannot read the image");
  const bool png = StartsWith(bytes, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'});
  const bool jpeg = StartsWith(bytes, {0xFF, 0xD8, 0xFF});
  if (!png && !jpeg) throw Error(path, 0, "not a PNG or JPEG image");
  if (png && !PngIsComplete(bytes)) throw Error(path, 0, "truncated PNG (no IEND chunk at its end)");
  if (jpeg && !JpegIsComplete(bytes)) {
    throw Error(path, 0, "truncated JPEG (no end-of-image marker at its end)");
  }
  // OpenCV logs decoder warnings itself; splinecal reports every problem once, as an Error.
  cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
  cv::Mat decoded;
  try {
    decoded = cv::imdecode(bytes, cv::IMREAD_GRAYSCALE);
  } catch (const cv::Exception& e) {
    throw Error(path, 0, "cannot decode the image: " + e.err);
  }
  if (decoded.empty() || decoded.type() != CV_8UC1) {
    throw Error(path, 0, "cannot decode the image (corrupt data)");
  }
  GrayImage image;
  image.width = decoded.cols;
  image.height = decoded.rows;
  image.pixels.resize(static_cast<size_t>(image.width) * image.height);
  for (int v = 0; v < image.height; ++v) {
    std::copy(decoded.ptr<uint8_t>(v), decoded.ptr<uint8_t>(v) + image.width,
              image.pixels.begin() + static_cast<size_t>(v) * image.width);
  }
  return image;
}

void WriteOverlayPng(const GrayImageView& image,
                     const std::vector<OverlayCorner>& corners,
                     const std::string& caption,
                     const std::string& path) {
  cv::Mat colour;
  cv::cvtColor(BorrowMat(image), colour, cv::COLOR_GRAY2BGR);
  const double scale = std::max(0.3, image.width / 2000.0);
  const int radius = std::max(3, image.width / 200);
  for (const OverlayCorner& corner : corners) {
    // Sub-pixel drawing: cv::circle takes fixed-point centres with `shift` fractional bits.
    const cv::Point centre(static_cast<int>(std::lround(corner.uv.x() * 16)),
                           static_cast<int>(std::lround(corner.uv.y() * 16)));
    cv::circle(colour, centre, radius * 16, cv::Scalar(0, 0, 255), 1, cv::LINE_AA, 4);
    cv::putText(colour, std::to_string(corner.id),
                cv::Point(static_cast<int>(corner.uv.x()) + radius,
                          static_cast<int>(corner.uv.y()) - radius),
                cv::FONT_HERSHEY_SIMPLEX, scale, cv::Scalar(0, 200, 0), 1, cv::LINE_AA);
  }
  cv::putText(colour, caption, cv::Point(8, 8 + static_cast<int>(24 * scale)),
              cv::FONT_HERSHEY_SIMPLEX, 1.4 * scale, cv::Scalar(255, 128, 0), 1, cv::LINE_AA);
  bool written = false;
  try {
    written = cv::imwrite(path, colour);
  } catch (const cv::Exception& e) {
    throw Error(path, 0, "cannot write the overlay: " + e.err);
  }
  if (!written) throw Error(path, 0, "cannot write the overlay");
}

}  // namespace splinecal
