#include "splinecal/detect/bag_image.h"

#include <opencv2/imgproc.hpp>

#include "image_decoders.h"
#include "opencv_view.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

struct Encoding {
  const char* name;
  int channels;
  int bytes_per_channel;
  int to_gray;  // cv::ColorConversionCodes to grey or to BGR (bayer); -1: none
};

// OpenCV names a Bayer pattern by the 2 x 2 cell starting at the second row and column, ROS by
// the first: ROS's rggb is OpenCV's BG (cv_bridge maps them the same way).
constexpr Encoding kEncodings[] = {
    {"mono8", 1, 1, -1},
    {"8UC1", 1, 1, -1},
    {"mono16", 1, 2, -1},
    {"16UC1", 1, 2, -1},
    {"bgr8", 3, 1, cv::COLOR_BGR2GRAY},
    {"rgb8", 3, 1, cv::COLOR_RGB2GRAY},
    {"bgra8", 4, 1, cv::COLOR_BGRA2GRAY},
    {"rgba8", 4, 1, cv::COLOR_RGBA2GRAY},
    {"bayer_rggb8", 1, 1, cv::COLOR_BayerBG2BGR},
    {"bayer_bggr8", 1, 1, cv::COLOR_BayerRG2BGR},
    {"bayer_gbrg8", 1, 1, cv::COLOR_BayerGR2BGR},
    {"bayer_grbg8", 1, 1, cv::COLOR_BayerGB2BGR},
};

// Larger images are refused: as image_decoders.h, a corrupt header must not ask for gigabytes.
void CheckSize(const ImageMessage& image, const std::string& where) {
  if (image.width == 0 || image.height == 0 ||
      static_cast<int64_t>(image.width) * image.height > kMaxImagePixels) {
    throw Error(where + StringPrintf(": image of %u x %u pixels", image.width, image.height));
  }
}

GrayImage Mono16ToGray(const cv::Mat& pixels, bool big_endian) {
  cv::Mat values = pixels.clone();
  if (big_endian) {
    for (int r = 0; r < values.rows; ++r) {
      uint16_t* row = values.ptr<uint16_t>(r);
      for (int c = 0; c < values.cols; ++c) row[c] = static_cast<uint16_t>((row[c] >> 8) | (row[c] << 8));
    }
  }
  double max_value = 0;
  cv::minMaxLoc(values, nullptr, &max_value);
  int bits = 0;
  while ((static_cast<int>(max_value) >> bits) != 0) ++bits;
  const int shift = std::max(0, bits - 8);
  GrayImage gray;
  gray.width = values.cols;
  gray.height = values.rows;
  gray.pixels.resize(static_cast<size_t>(gray.width) * gray.height);
  for (int r = 0; r < values.rows; ++r) {
    const uint16_t* row = values.ptr<uint16_t>(r);
    for (int c = 0; c < values.cols; ++c) {
      gray.pixels[static_cast<size_t>(r) * gray.width + c] = static_cast<uint8_t>(row[c] >> shift);
    }
  }
  return gray;
}

GrayImage FromMat(const cv::Mat& mat) {
  GrayImage gray;
  gray.width = mat.cols;
  gray.height = mat.rows;
  gray.pixels.resize(static_cast<size_t>(gray.width) * gray.height);
  for (int r = 0; r < mat.rows; ++r) {
    std::memcpy(gray.pixels.data() + static_cast<size_t>(r) * gray.width, mat.ptr(r),
                static_cast<size_t>(gray.width));
  }
  return gray;
}

}  // namespace

GrayImage BagImageToGray(const ImageMessage& image, const std::string& where) {
  if (image.compressed) {
    const std::vector<uint8_t> bytes(image.data.begin(), image.data.end());
    if (bytes.size() >= 8 && std::memcmp(bytes.data(), "\x89PNG\r\n\x1a\n", 8) == 0) {
      return DecodePng(bytes, where);
    }
    if (bytes.size() >= 3 && bytes[0] == 0xFF && bytes[1] == 0xD8 && bytes[2] == 0xFF) {
      return DecodeJpeg(bytes, where);
    }
    throw Error(where + ": compressed image of format '" + image.encoding +
                "' is neither PNG nor JPEG");
  }
  const Encoding* encoding = nullptr;
  for (const Encoding& e : kEncodings) {
    if (image.encoding == e.name) encoding = &e;
  }
  if (encoding == nullptr) {
    throw Error(where + ": image encoding '" + image.encoding +
                "' is not one of mono8, 8UC1, mono16, 16UC1, bgr8, rgb8, bgra8, rgba8, "
                "bayer_rggb8, bayer_bggr8, bayer_gbrg8, bayer_grbg8");
  }
  CheckSize(image, where);
  const uint64_t row_bytes =
      uint64_t{image.width} * encoding->channels * encoding->bytes_per_channel;
  if (image.step < row_bytes) {
    throw Error(where + StringPrintf(": image step %u is below its %llu bytes of a row",
                                     image.step, static_cast<unsigned long long>(row_bytes)));
  }
  const int type = CV_MAKETYPE(encoding->bytes_per_channel == 2 ? CV_16U : CV_8U,
                               encoding->channels);
  // ParseImageMessage checked height * step <= data size.
  const cv::Mat pixels(static_cast<int>(image.height), static_cast<int>(image.width), type,
                       const_cast<char*>(image.data.data()), image.step);
  if (encoding->bytes_per_channel == 2) return Mono16ToGray(pixels, image.big_endian);
  if (encoding->to_gray < 0) return FromMat(pixels);
  cv::Mat converted;
  cv::cvtColor(pixels, converted, encoding->to_gray);
  if (converted.channels() == 3) cv::cvtColor(cv::Mat(converted), converted, cv::COLOR_BGR2GRAY);
  return FromMat(converted);
}

std::string EncodeGrayPng(const GrayImageView& image) {
  return EncodePng(image.data, image.width, image.height, 1, image.stride);
}

}  // namespace splinecal
