// Reading images: real PNG and JPEG files, and each kind of bad file refused with its path.
#include "splinecal/detect/image_file.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>

#include <opencv2/imgcodecs.hpp>
#include <zlib.h>

#include "splinecal/error.h"
#include "testing/paths.h"
#include "testing/refusals.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

// Real images bundled in data/ (byte-identical to ../shared/data's euroc_april_frames/
// cam0_1403709395937837056.png and opencv_chessboard/left01.jpg), so these checks always run.
constexpr char kPng[] = "euroc_april_frames/cam0/data/1403709395937837056.png";
constexpr char kJpeg[] = "opencv_chessboard/cam0/1000000000.jpg";

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string ErrorOf(const std::string& path) {
  return testing::ErrorOf([&] { ReadGrayImage(path); });
}

TEST(ReadGrayImage, ReadsPngAndJpegAsOpenCvDecodesThem) {
  for (const char* relative : {kJpeg, kPng}) {
    const std::string path = testing::BundledDataPath(relative);
    const GrayImage image = ReadGrayImage(path);
    const cv::Mat reference = cv::imread(path, cv::IMREAD_GRAYSCALE);
    ASSERT_EQ(image.width, reference.cols);
    ASSERT_EQ(image.height, reference.rows);
    EXPECT_EQ(0, std::memcmp(image.pixels.data(), reference.data, image.pixels.size()));
  }
}

TEST(ReadGrayImage, ConvertsColourToGrey) {
  testing::TempDir dir;
  cv::Mat colour(4, 6, CV_8UC3, cv::Scalar(10, 200, 30));  // B, G, R
  const std::string path = dir.File("c.png");
  ASSERT_TRUE(cv::imwrite(path, colour));
  const GrayImage image = ReadGrayImage(path);
  EXPECT_EQ(image.width, 6);
  EXPECT_EQ(image.height, 4);
  EXPECT_NEAR(image.pixels[0], 0.114 * 10 + 0.587 * 200 + 0.299 * 30, 1.0);
}

TEST(ReadGrayImage, RefusesMissingNonImageAndTruncatedFiles) {
  testing::TempDir dir;
  EXPECT_THAT(ErrorOf(dir.File("absent.png")), HasSubstr("absent.png: cannot open the image"));
  EXPECT_THAT(ErrorOf(dir.Write("text.png", "not an image\n")),
              HasSubstr("text.png: not a PNG or JPEG image"));
  EXPECT_THAT(ErrorOf(dir.Write("empty.jpg", "")), HasSubstr("not a PNG or JPEG image"));
  const std::string png =
      ReadBytes(testing::BundledDataPath(kPng));
  EXPECT_THAT(ErrorOf(dir.Write("cut.png", png.substr(0, png.size() / 2))),
              HasSubstr("cut.png: truncated PNG"));
  const std::string jpeg = ReadBytes(testing::BundledDataPath(kJpeg));
  EXPECT_THAT(ErrorOf(dir.Write("cut.jpg", jpeg.substr(0, jpeg.size() / 2))),
              HasSubstr("cut.jpg: damaged JPEG (Premature end of JPEG file)"));
  // A PNG damaged in the middle but ending properly: its chunk CRC finds it (before libpng
  // would print its own message).
  std::string damaged = png;
  for (size_t i = 100; i < 2000; ++i) damaged[i] = static_cast<char>(0x55);
  EXPECT_THAT(ErrorOf(dir.Write("damaged.png", damaged)),
              HasSubstr("damaged.png: corrupt PNG (chunk IDAT at byte"));
  // The same for a JPEG: libjpeg's "Corrupt JPEG data" becomes the error (not a printed line).
  std::string damaged_jpeg = jpeg;
  for (size_t i = 2000; i < 2600; ++i) damaged_jpeg[i] = static_cast<char>(0x55);
  EXPECT_THAT(ErrorOf(dir.Write("damaged.jpg", damaged_jpeg)),
              HasSubstr("damaged.jpg: damaged JPEG (Corrupt JPEG data"));
}

// A PNG whose IHDR asks for 10^10 pixels (CRCs right): refused before any allocation.
TEST(ReadGrayImage, RefusesImplausiblyLargeImagesBeforeDecoding) {
  testing::TempDir dir;
  std::string png = "\x89PNG\r\n\x1a\n";
  const auto be32 = [](uint32_t v) {
    return std::string{static_cast<char>(v >> 24), static_cast<char>(v >> 16),
                       static_cast<char>(v >> 8), static_cast<char>(v)};
  };
  const auto chunk = [&](const std::string& type, const std::string& data) {
    const std::string body = type + data;
    const uint32_t crc = static_cast<uint32_t>(
        crc32(0L, reinterpret_cast<const Bytef*>(body.data()), static_cast<uInt>(body.size())));
    return be32(static_cast<uint32_t>(data.size())) + body + be32(crc);
  };
  png += chunk("IHDR", be32(100000) + be32(100000) + std::string("\x08\x00\x00\x00\x00", 5));
  png += chunk("IEND", "");
  EXPECT_THAT(ErrorOf(dir.Write("huge.png", png)),
              HasSubstr("huge.png: image of 100000 x 100000 pixels is beyond the plausible"));
}

// A PNG whose CRCs hold but whose header is invalid (bit depth 3): libpng's complaint becomes the
// error instead of a line it prints itself.
TEST(ReadGrayImage, RefusesAnInvalidPngHeaderWithLibpngsReason) {
  testing::TempDir dir;
  std::string png =
      ReadBytes(testing::BundledDataPath(kPng));
  png[24] = 3;  // IHDR: length (4), "IHDR" (4), width (4), height (4), then the bit depth
  const uint32_t crc = static_cast<uint32_t>(
      crc32(0L, reinterpret_cast<const Bytef*>(png.data() + 12), 17));
  for (int i = 0; i < 4; ++i) png[29 + i] = static_cast<char>(crc >> (24 - 8 * i));
  EXPECT_THAT(ErrorOf(dir.Write("depth3.png", png)),
              HasSubstr("depth3.png: cannot decode the PNG (Invalid IHDR data)"));
}

TEST(WriteOverlayPng, WritesAColourPngOfTheImageSize) {
  testing::TempDir dir;
  GrayImage image;
  image.width = 64;
  image.height = 48;
  image.pixels.assign(64 * 48, 100);
  const std::string path = dir.File("overlay.png");
  WriteOverlayPng(image.view(), {{7, Eigen::Vector2d(20.25, 30.5)}}, "cam0 1: 1 corners", path);
  const cv::Mat written = cv::imread(path, cv::IMREAD_UNCHANGED);
  ASSERT_FALSE(written.empty());
  EXPECT_EQ(written.cols, 64);
  EXPECT_EQ(written.rows, 48);
  EXPECT_EQ(written.channels(), 3);
  EXPECT_THROW(WriteOverlayPng(image.view(), {}, "", dir.File("no/such/dir/x.png")), Error);
}

}  // namespace
}  // namespace splinecal
