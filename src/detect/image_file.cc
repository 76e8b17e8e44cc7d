#include "splinecal/detect/image_file.h"

#include <filesystem>
#include <fstream>
#include <system_error>

#include <opencv2/imgproc.hpp>

#include "image_decoders.h"
#include "opencv_view.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

// Files larger than this are refused before they are read: no PNG or JPEG of kMaxImagePixels
// comes near it, and a renamed recording (a rosbag called 0.png) is not read whole.
constexpr uintmax_t kMaxImageFileBytes = uintmax_t{1} << 30;

bool StartsWith(const std::vector<uint8_t>& bytes, std::initializer_list<uint8_t> prefix) {
  return bytes.size() >= prefix.size() && std::equal(prefix.begin(), prefix.end(), bytes.begin());
}

}  // namespace

GrayImage ReadGrayImage(const std::string& path) {
  std::error_code error;
  const uintmax_t size = std::filesystem::file_size(path, error);
  if (error) throw Error(path, 0, "cannot open the image: " + error.message());
  if (size > kMaxImageFileBytes) {
    throw Error(path, 0, "a file of " + std::to_string(size) + " bytes is no camera image");
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error(path, 0, "cannot open the image");
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.read(reinterpret_cast<char*>(bytes.data()), static_cast<std::streamsize>(size));
  if (static_cast<uintmax_t>(in.gcount()) != size) throw Error(path, 0, "cannot read the image");
  if (StartsWith(bytes, {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'})) {
    return DecodePng(bytes, path);
  }
  if (StartsWith(bytes, {0xFF, 0xD8, 0xFF})) return DecodeJpeg(bytes, path);
  throw Error(path, 0, "not a PNG or JPEG image");
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
  std::string bytes;
  try {
    bytes = EncodePng(colour.data, colour.cols, colour.rows, 3,
                      static_cast<std::ptrdiff_t>(colour.step[0]));
  } catch (const Error& e) {
    throw Error(path, 0, std::string("cannot write the overlay: ") + e.what());
  }
  std::ofstream out(path, std::ios::binary);
  out.write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
  out.close();
  if (!out) throw Error(path, 0, "cannot write the overlay");
}

}  // namespace splinecal
