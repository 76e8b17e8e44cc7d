// `splinecal export` as a user runs it: a calibration folder in, a format's files out, and every
// refusal an exit 2 with one line and nothing written.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "testing/paths.h"
#include "testing/run_tool.h"

namespace splinecal {
namespace {

using testing::BundledDataPath;
using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RefusedInOneLine;
using testing::RunTool;
using testing::TempDir;

// A folder shaped like calibrate's output: the EuRoC camchain and a result.yaml with biases.
std::string CalibrateLikeFolder(const TempDir& dir) {
  dir.Write("calib/camchain-imucam.yaml",
            ReadFileText(BundledDataPath("euroc_april_frames/camchain_euroc.yaml")));
  dir.Write("calib/result.yaml",
            "gyro_bias: [0.001, 0.002, 0.003]\naccel_bias: [0.1, 0.2, 0.3]\nimu_rate_hz: 200\n");
  return dir.File("calib");
}

TEST(ExportCommand, WritesEachFormatsFiles) {
  TempDir dir;
  const std::string from = CalibrateLikeFolder(dir);
  const struct {
    const char* format;
    std::vector<std::string> files;
  } cases[] = {{"openvins", {"kalibr_imucam_chain.yaml", "kalibr_imu_chain.yaml"}},
               {"vins", {"vins_config.yaml", "cam0.yaml", "cam1.yaml"}},
               {"kalibr", {"camchain-imucam.yaml", "imu.yaml"}}};
  for (const auto& c : cases) {
    const std::string out = dir.File(std::string("out_") + c.format);
    const auto result = RunTool({"export", "--from", from, "--format", c.format, "--out", out});
    ASSERT_EQ(result.exit_code, 0) << c.format << ": " << result.err;
    for (const std::string& file : c.files) {
      EXPECT_TRUE(std::filesystem::is_regular_file(out + "/" + file)) << c.format << " " << file;
      EXPECT_THAT(result.out, HasSubstr("wrote " + out + "/" + file));
    }
    EXPECT_THAT(result.out, HasSubstr("assumed: EuRoC's ADIS16448"));
  }
}

TEST(ExportCommand, AModelTheFormatCannotHoldExitsTwoAndWritesNothing) {
  TempDir dir;
  const std::string from = CalibrateLikeFolder(dir);
  const std::string out = dir.File("out");
  const auto result = RunTool({"export", "--from", from, "--format", "basalt", "--out", out});
  EXPECT_TRUE(RefusedInOneLine(result, "basalt cannot hold cam0's camera model pinhole-radtan"));
  EXPECT_FALSE(std::filesystem::exists(out));
}

TEST(ExportCommand, BadFormatAndMissingFolderExitTwoWithOneLine) {
  TempDir dir;
  const std::string from = CalibrateLikeFolder(dir);
  auto result = RunTool({"export", "--from", from, "--format", "orbslam", "--out", dir.File("o")});
  EXPECT_TRUE(RefusedInOneLine(result, "openvins, vins, basalt, kalibr"));

  result = RunTool(
      {"export", "--from", dir.File("nowhere"), "--format", "vins", "--out", dir.File("o")});
  EXPECT_TRUE(RefusedInOneLine(result, "no camchain-imucam.yaml"));

  // A camera-only calibration (intrinsics' camchain.yaml) cannot feed a visual-inertial format.
  dir.Write("cams/camchain.yaml",
            ReadFileText(BundledDataPath("euroc_april_frames/camchain_euroc.yaml")));
  result = RunTool(
      {"export", "--from", dir.File("cams"), "--format", "openvins", "--out", dir.File("o")});
  EXPECT_EQ(result.exit_code, 2);
  EXPECT_THAT(result.err, HasSubstr("camera-only"));
  EXPECT_FALSE(std::filesystem::exists(dir.File("o")));
}

}  // namespace
}  // namespace splinecal
