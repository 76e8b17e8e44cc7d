// Bag images to the detector's grey (detect/bag_image.h) on the /enc/* topics of the fixtures
// (scripts/make_bag_fixtures.sh): one crop of a real AprilGrid frame in every encoding, in a
// ROS 1 bag (bz2 chunks) and an MCAP file (zstd chunks, CDR).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include <map>
#include <string>
#include <vector>

#include "splinecal/detect/bag_image.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_reader.h"
#include "testing/paths.h"

namespace splinecal {
namespace {

// The fixture script's crop: 96 x 64 pixels at (328, 208) of cam0's frame.
constexpr int kCropX = 328, kCropY = 208, kCropW = 96, kCropH = 64;

std::vector<uint8_t> ExpectedCrop() {
  const GrayImage frame = ReadGrayImage(
      testing::BundledDataPath("euroc_april_frames/cam0/data/1403709395937837056.png"));
  std::vector<uint8_t> crop;
  for (int y = kCropY; y < kCropY + kCropH; ++y) {
    for (int x = kCropX; x < kCropX + kCropW; ++x) crop.push_back(frame.pixels[y * frame.width + x]);
  }
  return crop;
}

std::vector<uint8_t> MatBytes(const cv::Mat& mat) {
  std::vector<uint8_t> bytes;
  for (int r = 0; r < mat.rows; ++r) bytes.insert(bytes.end(), mat.ptr(r), mat.ptr(r) + mat.cols);
  return bytes;
}

struct Decoded {
  ImageMessage message;
  std::string bytes;  // the message's data (message.data views into it)
  GrayImage gray;
};

// Every /enc/<encoding> topic of `file`, converted.
std::map<std::string, Decoded> ReadEncodings(const std::string& file) {
  const std::unique_ptr<BagReader> bag = OpenBag({testing::BundledDataPath("bags/" + file)});
  std::map<std::string, Decoded> out;
  BagMessage message;
  while (bag->Next(&message)) {
    const BagTopic& topic = bag->topics()[message.topic];
    if (topic.name.rfind("/enc/", 0) != 0) continue;
    Decoded& decoded = out[topic.name.substr(5)];
    decoded.bytes = std::string(message.data);
    message.data = decoded.bytes;
    decoded.message = ParseImageMessage(topic, message);
    decoded.gray = BagImageToGray(decoded.message, message.where);
  }
  return out;
}

cv::Mat Pixels(const Decoded& d, int type) {
  return cv::Mat(kCropH, kCropW, type, const_cast<char*>(d.message.data.data()), d.message.step);
}

class BagImageTest : public ::testing::TestWithParam<std::string> {};

TEST_P(BagImageTest, EveryEncodingBecomesTheGreyOpenCvMakes) {
  const std::map<std::string, Decoded> images = ReadEncodings(GetParam());
  ASSERT_EQ(images.size(), 13u);
  const std::vector<uint8_t> crop = ExpectedCrop();
  for (const auto& [name, d] : images) {
    EXPECT_EQ(d.gray.width, kCropW) << name;
    EXPECT_EQ(d.gray.height, kCropH) << name;
  }
  // Lossless grey: the crop itself, pixel for pixel. mono16 holds the grey in bits 9..2 (a
  // 10-bit sensor): shifted by the highest set bit it comes back exactly.
  for (const char* name : {"mono8", "8UC1", "png", "mono16"}) {
    EXPECT_EQ(images.at(name).gray.pixels, crop) << name;
  }
  // JPEG: as OpenCV decodes the same bytes to grey.
  const std::string& jpeg = images.at("jpeg").bytes;
  const Decoded& jpeg_image = images.at("jpeg");
  const cv::Mat jpeg_bytes(1, static_cast<int>(jpeg_image.message.data.size()), CV_8UC1,
                           const_cast<char*>(jpeg_image.message.data.data()));
  EXPECT_FALSE(jpeg.empty());
  EXPECT_EQ(jpeg_image.gray.pixels, MatBytes(cv::imdecode(jpeg_bytes, cv::IMREAD_GRAYSCALE)));
  // Colour: OpenCV's cvtColor of the same bytes; the four channel orders hold the same colours,
  // so all four greys are one image.
  const std::map<std::string, std::pair<int, int>> colour = {
      {"bgr8", {CV_8UC3, cv::COLOR_BGR2GRAY}}, {"rgb8", {CV_8UC3, cv::COLOR_RGB2GRAY}},
      {"bgra8", {CV_8UC4, cv::COLOR_BGRA2GRAY}}, {"rgba8", {CV_8UC4, cv::COLOR_RGBA2GRAY}}};
  for (const auto& [name, codes] : colour) {
    cv::Mat gray;
    cv::cvtColor(Pixels(images.at(name), codes.first), gray, codes.second);
    EXPECT_EQ(images.at(name).gray.pixels, MatBytes(gray)) << name;
    EXPECT_EQ(images.at(name).gray.pixels, images.at("bgr8").gray.pixels) << name;
  }
  // Bayer: OpenCV's bilinear demosaicing of the same bytes, then grey. OpenCV names the pattern
  // by its second row and column (ROS rggb = OpenCV BG).
  const std::map<std::string, int> bayer = {{"bayer_rggb8", cv::COLOR_BayerBG2BGR},
                                            {"bayer_bggr8", cv::COLOR_BayerRG2BGR},
                                            {"bayer_gbrg8", cv::COLOR_BayerGR2BGR},
                                            {"bayer_grbg8", cv::COLOR_BayerGB2BGR}};
  for (const auto& [name, code] : bayer) {
    cv::Mat bgr, gray;
    cv::cvtColor(Pixels(images.at(name), CV_8UC1), bgr, code);
    cv::cvtColor(bgr, gray, cv::COLOR_BGR2GRAY);
    EXPECT_EQ(images.at(name).gray.pixels, MatBytes(gray)) << name;
    // And the pattern is the right one: the demosaiced grey is near the grey of the true
    // colours (the bgr8 topic) inside the image. Measured on both fixtures: mean |difference|
    // 4.0 to 4.3 grey levels with the right pattern, 17.5 to 27.5 with any of the three others.
    double sum = 0;
    int count = 0;
    for (int y = 2; y < kCropH - 2; ++y) {
      for (int x = 2; x < kCropW - 2; ++x) {
        sum += std::abs(images.at(name).gray.pixels[y * kCropW + x] -
                        images.at("bgr8").gray.pixels[y * kCropW + x]);
        ++count;
      }
    }
    EXPECT_LT(sum / count, 10.0) << name;
  }
}

INSTANTIATE_TEST_SUITE_P(Fixtures, BagImageTest,
                         ::testing::Values("ros1_bz2.bag", "mcap_zstd.mcap"));

TEST(BagImageErrorTest, UnknownEncodingAndShortStepAreRefused) {
  const std::string pixels(64, '\0');
  ImageMessage image;
  image.width = 8;
  image.height = 8;
  image.step = 8;
  image.encoding = "yuv422";
  image.data = pixels;
  EXPECT_THROW(BagImageToGray(image, "a.bag: message"), Error);
  image.encoding = "rgb8";
  EXPECT_THROW(BagImageToGray(image, "a.bag: message"), Error);  // step 8 < 24 bytes a row
  image.compressed = true;
  image.encoding = "jpeg";
  EXPECT_THROW(BagImageToGray(image, "a.bag: message"), Error);  // not a JPEG
}

}  // namespace
}  // namespace splinecal
