// Images from bags (io/bag_messages.h) as the detector's 8-bit grey (docs/bags.md, "Encodings").
// The conversion lives here, in the image front end, because the core library has no image code.
#ifndef SPLINECAL_DETECT_BAG_IMAGE_H_
#define SPLINECAL_DETECT_BAG_IMAGE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/detect/gray_image.h"
#include "splinecal/io/bag_messages.h"

namespace splinecal {

// The 8-bit grey of a sensor_msgs/Image or CompressedImage:
// - mono8, 8UC1: as they are;
// - mono16 (16UC1): shifted right so that the highest bit set in this image becomes bit 7 (a
//   10-bit sensor's 0..1023 becomes 0..255 by >> 2, a 12-bit one's by >> 4): the full 8 bits
//   of contrast whatever the sensor's depth, where keeping the high byte would leave a 10-bit
//   image at 0..3;
// - bgr8, rgb8, bgra8, rgba8: 0.299 R + 0.587 G + 0.114 B (OpenCV's cvtColor, as ReadGrayImage);
// - bayer_rggb8, bayer_bggr8, bayer_gbrg8, bayer_grbg8: OpenCV's bilinear demosaicing to colour,
//   then the same weights;
// - CompressedImage: PNG or JPEG told by their first bytes, decoded as ReadGrayImage does.
// Throws splinecal::Error naming `where` for another encoding, a size that does not fit its data,
// or an image that does not decode.
GrayImage BagImageToGray(const ImageMessage& image, const std::string& where);

// An 8-bit grey PNG of `image` (lossless), the frames `splinecal bag extract` writes.
std::string EncodeGrayPng(const GrayImageView& image);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_BAG_IMAGE_H_
