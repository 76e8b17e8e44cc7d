// `splinecal bag info` and `splinecal bag extract` run as a user runs them, on the fixtures of
// data/bags/ (scripts/make_bag_fixtures.sh). The same recording in every format extracts to the
// same bytes.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "testing/paths.h"
#include "testing/run_tool.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::CountLines;
using testing::ReadFileText;
using testing::RunTool;
using testing::TempDir;

std::string Bag(const std::string& name) { return testing::BundledDataPath("bags/" + name); }

TEST(BagCommand, InfoListsTopicsCountsAndRates) {
  const auto result = RunTool({"bag", "info", Bag("ros1_lz4.bag")});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("format:    ROS 1 bag 2.0"));
  EXPECT_THAT(result.out, HasSubstr("messages:  103"));
  EXPECT_THAT(result.out, HasSubstr("/imu0               100 msgs  sensor_msgs/Imu     "
                                    "200.000 Hz  max gap 5.0 ms"));
  EXPECT_THAT(result.out, HasSubstr("std_msgs/String    (not read by splinecal)"));
  EXPECT_EQ(result.err, "");
}

TEST(BagCommand, UnindexedBagIsReadWithAWarning) {
  const auto result = RunTool({"bag", "info", Bag("ros1_unindexed.bag")});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.err, HasSubstr("warning: "));
  EXPECT_THAT(result.err, HasSubstr("linear scan"));
  EXPECT_THAT(result.out, HasSubstr("messages:  103"));
}

// The files of an extraction, path -> contents.
std::vector<std::pair<std::string, std::string>> Files(const std::string& dir) {
  std::vector<std::pair<std::string, std::string>> files;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    // result.yaml names the files and the format, which differ by design.
    if (!entry.is_regular_file() || entry.path().filename() == "result.yaml") continue;
    files.emplace_back(std::filesystem::relative(entry.path(), dir).string(),
                       ReadFileText(entry.path().string()));
  }
  std::sort(files.begin(), files.end());
  return files;
}

TEST(BagCommand, EveryFormatExtractsTheSameFolders) {
  TempDir dir;
  const std::vector<std::vector<std::string>> recordings = {
      {Bag("ros1_none.bag")},      {Bag("ros1_bz2.bag")},       {Bag("ros1_lz4.bag")},
      {Bag("ros1_unindexed.bag")}, {Bag("ros1_split_0.bag"), Bag("ros1_split_1.bag")},
      {Bag("mcap_none.mcap")},     {Bag("mcap_zstd.mcap")},     {Bag("mcap_lz4.mcap")},
      {Bag("mcap_unindexed.mcap")}, {Bag("mcap_unchunked.mcap")}, {Bag("rosbag2_db3")}};
  std::vector<std::pair<std::string, std::string>> first;
  for (size_t i = 0; i < recordings.size(); ++i) {
    const std::string out = dir.File("out" + std::to_string(i));
    std::vector<std::string> args = {"bag", "extract"};
    args.insert(args.end(), recordings[i].begin(), recordings[i].end());
    args.insert(args.end(), {"--out", out, "--topics", "/imu0,/cam0/image_raw,/cam1/image_raw"});
    const auto result = RunTool(args);
    ASSERT_EQ(result.exit_code, 0) << recordings[i][0] << ": " << result.err;
    const auto files = Files(out);
    if (i == 0) {
      first = files;
      ASSERT_EQ(files.size(), 5u);  // imu0/data.csv, cam0 and cam1: data.csv and one PNG
      EXPECT_EQ(CountLines(ReadFileText(out + "/imu0/data.csv")), 101);
      EXPECT_THAT(ReadFileText(out + "/cam0/data.csv"),
                  HasSubstr("\n1403715273512143104,1403715273512143104.png\n"));
      const std::string result = ReadFileText(out + "/result.yaml");
      EXPECT_THAT(result, HasSubstr("  imu0:\n    topic: \"/imu0\"\n    type: \"sensor_msgs/Imu\"\n"
                                    "    messages: 100\n    first_t_ns: 1403715273262142976\n"));
    } else {
      EXPECT_EQ(files, first) << recordings[i][0];
    }
  }
}

TEST(BagCommand, ReceiveTimeTakesTheRecordingTime) {
  TempDir dir;
  const auto result = RunTool({"bag", "extract", Bag("mcap_lz4.mcap"), "--out", dir.File("out"),
                               "--topics", "/imu0", "--bag-time", "receive"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  // Received 1 ms after the stamp 1403715273262142976 (the fixture script).
  EXPECT_THAT(ReadFileText(dir.File("out/imu0/data.csv")), HasSubstr("\n1403715273263142976,"));
}

TEST(BagCommand, BadInputIsOneLineAndWritesNothing) {
  TempDir dir;
  const std::string not_a_bag = dir.Write("imu.csv", "1,2,3\n");
  const std::vector<std::vector<std::string>> cases = {
      {"bag", "extract", Bag("ros1_lz4.bag"), "--out", dir.File("out"), "--topics", "/nope"},
      {"bag", "extract", Bag("ros1_lz4.bag"), "--out", dir.File("out"), "--topics", "/other"},
      {"bag", "extract", Bag("ros1_lz4.bag"), "--out", dir.File("out"), "--bag-time", "x"},
      {"bag", "extract", not_a_bag, "--out", dir.File("out")},
      {"bag", "info", dir.File("absent.bag")},
      {"bag", "info"},
  };
  for (const auto& args : cases) {
    const auto result = RunTool(args);
    EXPECT_EQ(result.exit_code, 2) << args.back() << ": " << result.err;
    EXPECT_EQ(CountLines(result.err), 1) << result.err;
    EXPECT_FALSE(std::filesystem::exists(dir.File("out/imu0"))) << args.back();
  }
}

}  // namespace
}  // namespace splinecal
