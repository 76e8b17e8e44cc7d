// PNG to 8-bit grey with libpng (image_decoders.h).
#include <png.h>
#include <zlib.h>

#include <csetjmp>
#include <cstring>

#include "image_decoders.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

uint32_t BigEndian32(const std::vector<uint8_t>& bytes, size_t at) {
  return (uint32_t{bytes[at]} << 24) | (uint32_t{bytes[at + 1]} << 16) |
         (uint32_t{bytes[at + 2]} << 8) | uint32_t{bytes[at + 3]};
}

std::string TooLarge(int64_t width, int64_t height) {
  return "image of " + std::to_string(width) + " x " + std::to_string(height) +
         " pixels is beyond the plausible " + std::to_string(kMaxImagePixels) + " pixels";
}

// Walks the chunks (length, type, data, CRC-32 of type and data): every CRC must hold, the first
// chunk must be an IHDR of a plausible size, the last IEND. Empty when the file is whole; else
// what is wrong. (libpng checks CRCs of critical chunks too, but a truncated file is only found
// when the decoder runs out of data.)
std::string PngStructureProblem(const std::vector<uint8_t>& bytes) {
  size_t at = 8;  // after the signature
  while (at + 12 <= bytes.size()) {
    const uint32_t length = BigEndian32(bytes, at);
    if (length > bytes.size() - at - 12) break;  // runs past the end
    const std::string type(bytes.begin() + at + 4, bytes.begin() + at + 8);
    const size_t crc_at = at + 8 + length;
    const uint32_t computed =
        static_cast<uint32_t>(crc32(crc32(0L, Z_NULL, 0), bytes.data() + at + 4, length + 4));
    if (BigEndian32(bytes, crc_at) != computed) {
      return "corrupt PNG (chunk " + type + " at byte " + std::to_string(at) +
             " fails its CRC check)";
    }
    if (at == 8) {
      if (type != "IHDR" || length < 8) return "corrupt PNG (it does not start with IHDR)";
      const int64_t width = BigEndian32(bytes, at + 8), height = BigEndian32(bytes, at + 12);
      if (width == 0 || height == 0) return "corrupt PNG (an image of no pixels)";
      // Each side is below 2^32, so the product fits in int64.
      if (width * height > kMaxImagePixels) return TooLarge(width, height);
    }
    if (type == "IEND") return "";
    at = crc_at + 4;
  }
  return "truncated PNG (it ends before its IEND chunk)";
}

struct PngInput {
  const std::vector<uint8_t>* bytes;
  size_t at = 8;
};

struct PngErrors {
  std::jmp_buf jump;
  char message[256] = {};
};

void ReadFromMemory(png_structp png, png_bytep out, png_size_t count) {
  PngInput* input = static_cast<PngInput*>(png_get_io_ptr(png));
  if (count > input->bytes->size() - input->at) png_error(png, "read past the end of the file");
  std::memcpy(out, input->bytes->data() + input->at, count);
  input->at += count;
}

void OnPngError(png_structp png, png_const_charp message) {
  PngErrors* errors = static_cast<PngErrors*>(png_get_error_ptr(png));
  std::snprintf(errors->message, sizeof(errors->message), "%s", message);
  std::longjmp(errors->jump, 1);
}

// Warnings (an sRGB profile libpng dislikes, say) do not make an image wrong: not printed.
void OnPngWarning(png_structp, png_const_charp) {}

// The decoding proper. setjmp lives here, with every object it may come back to owned by the
// caller, so nothing local is left indeterminate or undestroyed by a longjmp. False on a libpng
// error (errors->message says which).
bool DecodePngInto(png_structp png, png_infop info, PngErrors* errors, GrayImage* image) {
  if (setjmp(errors->jump) != 0) return false;
  png_set_sig_bytes(png, 8);
  png_read_info(png, info);
  const png_uint_32 width = png_get_image_width(png, info);
  const png_uint_32 height = png_get_image_height(png, info);
  const int color_type = png_get_color_type(png, info);
  const int bit_depth = png_get_bit_depth(png, info);
  // To 8-bit grey: palettes and low bit depths expanded, alpha dropped, colour weighted as
  // OpenCV and ITU-R BT.601 do (0.299 R + 0.587 G + 0.114 B).
  if (color_type == PNG_COLOR_TYPE_PALETTE) png_set_palette_to_rgb(png);
  if (color_type == PNG_COLOR_TYPE_GRAY && bit_depth < 8) png_set_expand_gray_1_2_4_to_8(png);
  if (png_get_valid(png, info, PNG_INFO_tRNS)) png_set_tRNS_to_alpha(png);
  // 16-bit samples span the full range (the PNG standard scales n significant bits up to 16):
  // their high byte is the 8-bit value, as OpenCV reads them.
  if (bit_depth == 16) png_set_strip_16(png);
  png_set_strip_alpha(png);
  if (color_type & PNG_COLOR_MASK_COLOR || color_type == PNG_COLOR_TYPE_PALETTE) {
    png_set_rgb_to_gray(png, 1, 0.299, 0.587);
  }
  png_read_update_info(png, info);
  if (png_get_channels(png, info) != 1 || png_get_bit_depth(png, info) != 8) {
    png_error(png, "unsupported pixel format");
  }
  image->width = static_cast<int>(width);
  image->height = static_cast<int>(height);
  image->pixels.resize(static_cast<size_t>(width) * height);
  for (int pass = png_set_interlace_handling(png); pass > 0; --pass) {
    for (png_uint_32 v = 0; v < height; ++v) {
      png_read_row(png, image->pixels.data() + static_cast<size_t>(v) * width, nullptr);
    }
  }
  png_read_end(png, nullptr);
  return true;
}

}  // namespace

GrayImage DecodePng(const std::vector<uint8_t>& bytes, const std::string& path) {
  const std::string problem = PngStructureProblem(bytes);
  if (!problem.empty()) throw Error(path, 0, problem);
  PngErrors errors;
  PngInput input{&bytes};
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, &errors, &OnPngError,
                                           &OnPngWarning);
  png_infop info = png != nullptr ? png_create_info_struct(png) : nullptr;
  if (png == nullptr || info == nullptr) {
    png_destroy_read_struct(&png, &info, nullptr);
    throw Error(path, 0, "cannot decode the PNG (out of memory)");
  }
  png_set_read_fn(png, &input, &ReadFromMemory);
  GrayImage image;
  const bool decoded = DecodePngInto(png, info, &errors, &image);
  png_destroy_read_struct(&png, &info, nullptr);
  if (!decoded) throw Error(path, 0, std::string("cannot decode the PNG (") + errors.message + ")");
  return image;
}

}  // namespace splinecal
