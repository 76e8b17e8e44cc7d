// 8-bit grey or BGR pixels to PNG bytes with libpng's simplified API (image_decoders.h).
#include <png.h>

#include <cstring>
#include <string>

#include "image_decoders.h"
#include "splinecal/error.h"

namespace splinecal {

std::string EncodePng(
    const uint8_t* pixels, int width, int height, int channels, std::ptrdiff_t stride) {
  png_image png;
  std::memset(&png, 0, sizeof(png));
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width);
  png.height = static_cast<png_uint_32>(height);
  png.format = channels == 3 ? PNG_FORMAT_BGR : PNG_FORMAT_GRAY;
  // Speed over size, as OpenCV's encoder defaults to (its compression level 1): no row filters,
  // zlib level 3.
  png.flags = PNG_IMAGE_FLAG_FAST;
  const png_int_32 row_stride = static_cast<png_int_32>(stride);
  // The first call measures, the second writes (libpng's documented two-pass use).
  png_alloc_size_t size = 0;
  if (png_image_write_to_memory(&png,
                                nullptr,
                                &size,
                                /*convert_to_8bit=*/0,
                                pixels,
                                row_stride,
                                /*colormap=*/nullptr) &&
      size > 0) {
    std::string bytes(size, '\0');
    if (png_image_write_to_memory(&png, bytes.data(), &size, 0, pixels, row_stride, nullptr)) {
      bytes.resize(size);
      return bytes;
    }
  }
  const std::string message = png.message;
  png_image_free(&png);
  throw Error("PNG encoding failed: " + message);
}

}  // namespace splinecal
