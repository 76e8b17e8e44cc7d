// The input gates through the tool, on real EuRoC imu_april files: a wrong target layout, a
// wrong image size and microsecond IMU timestamps each exit 2 with one line naming the file, the
// cause and the fix, and write nothing (docs/reliability.md, "Inputs that calibrate to a wrong
// answer"). The right inputs pass the gates (camera/target_layout_check_test.cc and the other
// unit tests; here the commands get past them to their next input).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "testing/microsecond_imu.h"
#include "testing/run_tool.h"
#include "testing/shared_data.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::CountLines;
using testing::RunTool;
using testing::SharedDataPath;
using testing::TempDir;

const char kGrid7x7[] =
    "target_type: aprilgrid\ntagCols: 7\ntagRows: 7\ntagSize: 0.088\ntagSpacing: 0.3\n";
const char kSpacing02[] =
    "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.2\n";

std::string April(const std::string& file) { return SharedDataPath("euroc_imu_april/" + file); }

// Exit 2, one line on stderr containing every part, nothing written at `out`.
void ExpectRefused(const std::vector<std::string>& args,
                   const std::string& out,
                   const std::vector<std::string>& parts) {
  const testing::ToolResult result = RunTool(args);
  EXPECT_EQ(result.exit_code, 2) << result.err;
  EXPECT_EQ(CountLines(result.err), 1) << result.err;
  for (const std::string& part : parts) EXPECT_THAT(result.err, HasSubstr(part));
  EXPECT_FALSE(std::filesystem::exists(out)) << out;
}

std::vector<std::string> Intrinsics(const std::string& target,
                                    const std::string& resolution,
                                    const std::string& out) {
  return {"intrinsics", "--observations", April("observations.csv"), "--target", target,
          "--models", "pinhole-radtan,pinhole-radtan", "--resolution", resolution, "--out", out,
          "--quiet"};
}

TEST(InputGates, IntrinsicsRefusesASevenBySevenGridForTheSixBySixBoard) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  TempDir dir;
  const std::string grid = dir.Write("aprilgrid.yaml", kGrid7x7);
  ExpectRefused(Intrinsics(grid, "752x480", dir.File("out")),
                dir.File("out"),
                {"observations.csv: the corners fit a 6 x 6 aprilgrid (tagCols x tagRows) with "
                 "tagSpacing 0.30, not the 7 x 7 aprilgrid (tagSpacing 0.30) of " +
                     grid,
                 "fix tagCols/tagRows in " + grid});
}

TEST(InputGates, IntrinsicsRefusesAWrongSpacingRatio) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  TempDir dir;
  const std::string grid = dir.Write("aprilgrid.yaml", kSpacing02);
  ExpectRefused(Intrinsics(grid, "752x480", dir.File("out")),
                dir.File("out"),
                {"observations.csv: the corners fit tagSpacing 0.3", "not the 0.20 of " + grid,
                 "fix tagSpacing in " + grid});
}

TEST(InputGates, IntrinsicsRefusesAResolutionTheCornersDoNotFit) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  TempDir dir;
  ExpectRefused(Intrinsics(April("aprilgrid.yaml"), "640x480", dir.File("out")),
                dir.File("out"),
                {"observations.csv: cam0: 2083 of 179524 corners lie outside its 640 x 480 image "
                 "from --resolution 640x480 (largest u 747.7, v 476.3); the image is at least "
                 "749 x 477 (e.g. 752 x 480)"});
}

TEST(InputGates, CalibrateRefusesTheWrongGridBeforeReadingTheImu) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  TempDir dir;
  const std::string grid = dir.Write("aprilgrid.yaml", kGrid7x7);
  ExpectRefused({"calibrate", "--imu", April("imu0.csv"), "--observations",
                 April("observations.csv"), "--camchain", April("camchain_euroc.yaml"),
                 "--target", grid, "--out", dir.File("out"), "--quiet"},
                dir.File("out"),
                {"the corners fit a 6 x 6 aprilgrid", "not the 7 x 7 aprilgrid"});
}

// Every command that reads IMU samples refuses microsecond timestamps with the same line.
TEST(InputGates, EveryImuCommandRefusesMicrosecondTimestamps) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/imu0.csv");
  TempDir dir;
  const std::string imu = testing::WriteMicrosecondImu(dir, April("imu0.csv"));
  const std::string out = dir.File("out");
  // The second file of each command is never reached: the IMU is read first (calibrate: last,
  // after the observations, which pass).
  const std::string poses = SharedDataPath("euroc_v1_01_easy/groundtruth.csv");
  const std::vector<std::vector<std::string>> commands = {
      {"allan", "--imu", imu, "--out", out, "--quiet"},
      {"integrate", "--imu", imu, "--groundtruth", poses, "--out", out, "--quiet"},
      {"fit", "--imu", imu, "--poses", poses, "--out", out, "--quiet"},
      {"align", "--imu", imu, "--camera-poses", poses, "--out", out, "--quiet"},
      {"calibrate", "--imu", imu, "--observations", April("observations.csv"), "--camchain",
       April("camchain_euroc.yaml"), "--target", April("aprilgrid.yaml"), "--out", out, "--quiet"}};
  for (const std::vector<std::string>& args : commands) {
    SCOPED_TRACE(args[0]);
    ExpectRefused(args,
                  out,
                  {imu + ": IMU sample rate", "the timestamps look like microseconds",
                   "multiply them by 1000"});
  }
}

}  // namespace
}  // namespace splinecal
