// JPEG to 8-bit grey with libjpeg (image_decoders.h).
#include <cstdio>
// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>

#include <csetjmp>

#include "image_decoders.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

// libjpeg reports a fatal error through error_exit, which must not return (longjmp back to the
// decoder's caller), and damage it can step over ("Corrupt JPEG data: ...", "Premature end of
// JPEG file") through emit_message at level -1, by default printing it and decoding made-up
// rows. Both end the frame here, with libjpeg's message.
struct JpegErrors {
  jpeg_error_mgr manager;
  std::jmp_buf jump;
  char message[JMSG_LENGTH_MAX] = {};
  bool damaged = false;
  bool too_large = false;
};

void JpegErrorExit(j_common_ptr info) {
  JpegErrors* errors = reinterpret_cast<JpegErrors*>(info->err);
  (*info->err->format_message)(info, errors->message);
  std::longjmp(errors->jump, 1);
}

void JpegEmitMessage(j_common_ptr info, int level) {
  JpegErrors* errors = reinterpret_cast<JpegErrors*>(info->err);
  if (level < 0 && !errors->damaged) {
    (*info->err->format_message)(info, errors->message);
    errors->damaged = true;
  }
}

// The decoding proper. setjmp lives here, with every object it may come back to owned by the
// caller, so that a longjmp leaves nothing local indeterminate or undestroyed. False on a fatal
// libjpeg error or an image beyond kMaxImagePixels.
bool DecodeJpegInto(jpeg_decompress_struct* info,
                    JpegErrors* errors,
                    const std::vector<uint8_t>& bytes,
                    GrayImage* image) {
  if (setjmp(errors->jump) != 0) return false;
  jpeg_create_decompress(info);
  jpeg_mem_src(info, bytes.data(), static_cast<unsigned long>(bytes.size()));
  jpeg_read_header(info, TRUE);
  if (int64_t{info->image_width} * info->image_height > kMaxImagePixels) {
    errors->too_large = true;
    return false;
  }
  info->out_color_space = JCS_GRAYSCALE;  // the Y of YCbCr: 0.299 R + 0.587 G + 0.114 B
  jpeg_start_decompress(info);
  image->width = static_cast<int>(info->output_width);
  image->height = static_cast<int>(info->output_height);
  image->pixels.resize(static_cast<size_t>(image->width) * image->height);
  while (info->output_scanline < info->output_height) {
    JSAMPROW row = image->pixels.data() + static_cast<size_t>(info->output_scanline) * image->width;
    jpeg_read_scanlines(info, &row, 1);
  }
  jpeg_finish_decompress(info);
  return true;
}

}  // namespace

GrayImage DecodeJpeg(const std::vector<uint8_t>& bytes, const std::string& path) {
  jpeg_decompress_struct info;
  JpegErrors errors;
  info.err = jpeg_std_error(&errors.manager);
  errors.manager.error_exit = &JpegErrorExit;
  errors.manager.emit_message = &JpegEmitMessage;
  GrayImage image;
  const bool decoded = DecodeJpegInto(&info, &errors, bytes, &image);
  const int64_t width = info.image_width, height = info.image_height;
  jpeg_destroy_decompress(&info);
  if (errors.too_large) {
    throw Error(path, 0, "image of " + std::to_string(width) + " x " + std::to_string(height) +
                             " pixels is beyond the plausible " +
                             std::to_string(kMaxImagePixels) + " pixels");
  }
  if (!decoded) throw Error(path, 0, std::string("cannot decode the JPEG (") + errors.message + ")");
  if (errors.damaged) throw Error(path, 0, std::string("damaged JPEG (") + errors.message + ")");
  return image;
}

}  // namespace splinecal
