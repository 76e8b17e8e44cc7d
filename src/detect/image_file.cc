#include "splinecal/detect/image_file.h"

#include <cstdio>
#include <fstream>
#include <iterator>

#include <csetjmp>

#include <jpeglib.h>
#include <zlib.h>

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

// Walks a PNG's chunks (length, type, data, CRC-32 of type and data) and checks every CRC and
// that the last chunk is IEND. Empty when the file is whole; else what is wrong. libpng would
// find most of this too, but prints its own message to stderr first.
std::string PngProblem(const std::vector<uint8_t>& bytes) {
  size_t at = 8;  // after the signature
  while (at + 12 <= bytes.size()) {
    const uint32_t length = (uint32_t{bytes[at]} << 24) | (uint32_t{bytes[at + 1]} << 16) |
                            (uint32_t{bytes[at + 2]} << 8) | uint32_t{bytes[at + 3]};
    if (length > bytes.size() - at - 12) break;  // runs past the end
    const std::string type(bytes.begin() + at + 4, bytes.begin() + at + 8);
    const size_t crc_at = at + 8 + length;
    const uint32_t stored = (uint32_t{bytes[crc_at]} << 24) | (uint32_t{bytes[crc_at + 1]} << 16) |
                            (uint32_t{bytes[crc_at + 2]} << 8) | uint32_t{bytes[crc_at + 3]};
    const uint32_t computed =
        static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data() + at + 4, length + 4));
    if (stored != computed) {
      return "corrupt PNG (chunk " + type + " at byte " + std::to_string(at) +
             " fails its CRC check)";
    }
    if (type == "IEND") return "";
    at = crc_at + 4;
  }
  return "truncated PNG (it ends before its IEND chunk)";
}

// A JPEG ends with the end-of-image marker FF D9 (some writers pad a few bytes after it).
bool JpegIsComplete(const std::vector<uint8_t>& bytes) {
  const size_t tail = std::min<size_t>(bytes.size(), 64);
  for (size_t i = bytes.size() - tail; i + 1 < bytes.size(); ++i) {
    if (bytes[i] == 0xFF && bytes[i + 1] == 0xD9) return true;
  }
  return false;
}

// libjpeg reports a fatal error through error_exit (which must not return: longjmp back to the
// decoder's caller) and a recoverable one ("Corrupt JPEG data: ...") through emit_message at level
// -1, by default printing it and decoding garbage. Both become an Error here, with the message.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
  bool corrupt = false;
};

void JpegErrorExit(j_common_ptr info) {
  JpegErrors* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void JpegEmitMessage(j_common_ptr info, int level) {
  JpegErrors* errors = reinterpret_cast<JpegErrors*>(info->err);
  if (level < 0 && !errors->corrupt) {
    (*info->err->format_message)(info, errors->message);
    errors->corrupt = true;
  }
}

// Decodes a JPEG to 8-bit grey with libjpeg (Y of YCbCr, as OpenCV does). Nothing with a
// destructor is created between setjmp and a longjmp that may return to it.
GrayImage DecodeJpeg(const std::vector<uint8_t>& bytes, const std::string& path) {
  GrayImage image;
  jpeg_decompress_struct info;
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = &JpegErrorExit;
  errors.manager.emit_message = &JpegEmitMessage;
  if (setjmp(errors.jump) != 0) {
    jpeg_destroy_decompress(&info);
    throw Error(path, 0, std::string("corrupt JPEG (") + errors.message + ")");
  }
  jpeg_create_decompress(&info);
  jpeg_mem_src(&info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(&info, TRUE);
  info.out_color_space = JCS_GRAYSCALE;
  jpeg_start_decompress(&info);
  image.width = static_cast<int>(info.output_width);
  image.height = static_cast<int>(info.output_height);
  image.pixels.resize(static_cast<size_t>(image.width) * image.height);
  while (info.output_scanline < info.output_height) {
    JSAMPROW row = image.pixels.data() + static_cast<size_t>(info.output_scanline) * image.width;
    jpeg_read_scanlines(&info, &row, 1);
  }
  jpeg_finish_decompress(&info);
  jpeg_destroy_decompress(&info);
  if (errors.corrupt) throw Error(path, 0, std::string("corrupt JPEG (") + errors.message + ")");
  return image;
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
  if (png) {
    const std::string problem = PngProblem(bytes);
    if (!problem.empty()) throw Error(path, 0, problem);
  }
  if (jpeg && !JpegIsComplete(bytes)) {
    throw Error(path, 0, "truncated JPEG (no end-of-image marker at its end)");
  }
  if (jpeg) return DecodeJpeg(bytes, path);
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
