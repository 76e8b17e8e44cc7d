// Listing camera image folders: the EuRoC/ASL layout and plain <t_ns>.png folders, and what is
// refused or reported.
#include "splinecal/io/image_folder.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "splinecal/error.h"
#include "testing/refusals.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

using testing::ErrorOf;

// The message with which ListImageFolder refuses the folder `name` of `dir`.
std::string ListingError(const testing::TempDir& dir, const std::string& name) {
  return ErrorOf([&] { ListImageFolder(dir.File(name)); });
}

TEST(ListImageFolder, ReadsAnEurocCameraFolderInTimeOrder) {
  testing::TempDir dir;
  dir.Write("cam0/data.csv",
            "#timestamp [ns],filename\r\n"
            "1403709396037837056,1403709396037837056.png\r\n"
            "1403709395937837056,1403709395937837056.png\r\n");
  dir.Write("cam0/data/1403709395937837056.png", "x");
  dir.Write("cam0/data/1403709396037837056.png", "x");
  const ImageFolder folder = ListImageFolder(dir.File("cam0"));
  EXPECT_TRUE(folder.euroc);
  ASSERT_EQ(folder.frames.size(), 2u);
  EXPECT_EQ(folder.frames[0].t_ns, 1403709395937837056);
  EXPECT_EQ(folder.frames[0].path, dir.File("cam0/data/1403709395937837056.png"));
  EXPECT_EQ(folder.frames[0].origin, dir.File("cam0/data.csv") + ":3");
  EXPECT_TRUE(folder.warnings.empty());
}

TEST(ListImageFolder, AMissingImageOfDataCsvIsAWarningNamingTheLine) {
  testing::TempDir dir;
  dir.Write("cam0/data.csv", "#timestamp [ns],filename\n100,100.png\n200,200.png\n");
  dir.Write("cam0/data/100.png", "x");
  const ImageFolder folder = ListImageFolder(dir.File("cam0"));
  ASSERT_EQ(folder.frames.size(), 1u);
  ASSERT_EQ(folder.warnings.size(), 1u);
  EXPECT_THAT(folder.warnings[0], HasSubstr("data.csv:3: image "));
  EXPECT_THAT(folder.warnings[0], HasSubstr("200.png is missing"));
}

TEST(ListImageFolder, ReadsAPlainFolderOfTimestampNamedImages) {
  testing::TempDir dir;
  dir.Write("imgs/300.jpg", "x");
  dir.Write("imgs/100.PNG", "x");
  dir.Write("imgs/200.jpeg", "x");
  dir.Write("imgs/notes.txt", "ignored");
  dir.Write("imgs/frame_a.png", "x");
  std::filesystem::create_directories(dir.File("imgs/400.png"));  // a folder with an image name
  const ImageFolder folder = ListImageFolder(dir.File("imgs"));
  EXPECT_FALSE(folder.euroc);
  ASSERT_EQ(folder.frames.size(), 3u);
  EXPECT_EQ(folder.frames[0].t_ns, 100);
  EXPECT_EQ(folder.frames[2].t_ns, 300);
  ASSERT_EQ(folder.warnings.size(), 2u);
  const std::string warnings = folder.warnings[0] + "\n" + folder.warnings[1];
  EXPECT_THAT(warnings, HasSubstr("frame_a.png: the name is not a timestamp"));
  EXPECT_THAT(warnings, HasSubstr("400.png: not a regular file"));
}

TEST(ListImageFolder, RefusesWhatNamesNoFrames) {
  testing::TempDir dir;
  EXPECT_THAT(ListingError(dir, "absent"), HasSubstr("no such folder"));
  dir.Write("file", "x");
  EXPECT_THAT(ListingError(dir, "file"), HasSubstr("not a folder"));
  dir.Write("empty/readme.txt", "x");
  EXPECT_THAT(ListingError(dir, "empty"), HasSubstr("no images named <t_ns>.png"));
  dir.Write("allmissing/data.csv", "1,1.png\n");
  EXPECT_THAT(ListingError(dir, "allmissing"),
              HasSubstr("data.csv: no image of data.csv exists under data/"));
}

TEST(ListImageFolder, RefusesMalformedDataCsvRowsWithFileAndLine) {
  testing::TempDir dir;
  dir.Write("a/data.csv", "#timestamp [ns],filename\n100,100.png,extra\n");
  EXPECT_THAT(ListingError(dir, "a"), HasSubstr("a/data.csv:2: expected 2 columns"));
  dir.Write("b/data.csv", "1.5e9,x.png\n");
  EXPECT_THAT(ListingError(dir, "b"), HasSubstr("b/data.csv:1:1: timestamp [ns]"));
  dir.Write("c/data.csv", "100,100.png\n100,other.png\n");
  dir.Write("c/data/100.png", "x");
  dir.Write("c/data/other.png", "x");
  EXPECT_THAT(ListingError(dir, "c"), HasSubstr("c/data.csv:2: timestamp 100 also names"));
}

}  // namespace
}  // namespace splinecal
