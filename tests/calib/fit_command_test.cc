// `splinecal fit` end to end: the binary on simulated files, and the EuRoC excerpt.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <sstream>
#include <string>

#include "calib/fit_test_data.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/poses.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using testing::CountLines;
using testing::FitData;
using testing::FitScenario;
using ::testing::HasSubstr;
using testing::MakeFitData;
using testing::ReadFileText;
using testing::RunTool;
using testing::TempDir;

struct Files {
  std::string imu;
  std::string poses;
};

Files WriteScenario(const TempDir& dir, const FitData& data) {
  std::ostringstream imu;
  WriteEurocImu(data.imu, &imu);
  std::ostringstream poses;
  WriteTumTrajectory(data.poses, &poses);
  return {dir.Write("imu0.csv", imu.str()), dir.Write("poses.txt", poses.str())};
}

TEST(FitCommand, WritesEveryOutputAndTheEstimates) {
  TempDir dir;
  FitScenario scenario;
  scenario.duration_s = 8.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  const FitData data = MakeFitData(scenario);
  const Files files = WriteScenario(dir, data);
  const auto result = RunTool({"fit",
                               "--imu",
                               files.imu,
                               "--poses",
                               files.poses,
                               "--out",
                               dir.File("out"),
                               "--knot-spacing",
                               "0.1"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.err, HasSubstr("fit: iteration"));  // progress on stderr
  EXPECT_THAT(result.out, HasSubstr("gyro_bias"));
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(dir.File("out")), 1);
  const YAML::Node yaml = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
  for (const char* key : {"gyro_bias",
                          "gyro_bias_std",
                          "accel_bias",
                          "accel_bias_std",
                          "gravity_w",
                          "gravity_w_std",
                          "time_offset_s",
                          "residual_rms",
                          "iterations",
                          "final_cost",
                          "solve_time_s",
                          "knot_spacing_s",
                          "warnings"}) {
    EXPECT_TRUE(yaml[key]) << key;
  }
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(yaml["gyro_bias"][a].as<double>(),
                scenario.gyro_bias[a],
                3.0 * yaml["gyro_bias_std"][a].as<double>());
  }
  EXPECT_EQ(CountLines(ReadFileText(dir.File("out/residuals.csv"))),
            1 + static_cast<int>(data.imu.size()));
  EXPECT_EQ(CountLines(ReadFileText(dir.File("out/spline.csv"))),
            1 + data.truth.num_control_poses());
  const std::string html = ReadFileText(dir.File("out/report.html"));
  EXPECT_THAT(html, HasSubstr("<svg"));
  EXPECT_THAT(html, HasSubstr("Residuals"));
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/pose_residuals.csv")));
}

TEST(FitCommand, QuietSilencesProgress) {
  TempDir dir;
  FitScenario scenario;
  scenario.duration_s = 5.0;
  const Files files = WriteScenario(dir, MakeFitData(scenario));
  const auto result = RunTool({"fit",
                               "--imu",
                               files.imu,
                               "--poses",
                               files.poses,
                               "--out",
                               dir.File("out"),
                               "--knot-spacing",
                               "0.1",
                               "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");
}

TEST(FitCommand, BadInputIsOneLineExitTwoAndNoOutput) {
  TempDir dir;
  FitScenario scenario;
  scenario.duration_s = 5.0;
  FitData data = MakeFitData(scenario);
  for (StampedPose& p : data.poses) p.t_ns += 3'600'000'000'000;  // an hour later
  const Files files = WriteScenario(dir, data);
  // Kalibr's imu.yaml where the samples belong (Kalibr's own flag for it is --imu).
  const std::string imu_yaml =
      dir.Write("imu.yaml",
                "%YAML:1.0\naccelerometer_noise_density: 2.0e-3\ngyroscope_noise_density: "
                "1.7e-4\nupdate_rate: 200.0\n");
  const std::vector<std::vector<std::string>> cases = {
      {"fit", "--imu", files.imu, "--poses", files.poses, "--out", dir.File("out")},
      {"fit", "--imu", imu_yaml, "--poses", files.poses, "--out", dir.File("out")},
      {"fit", "--imu", files.imu, "--out", dir.File("out")},
      {"fit",
       "--imu",
       files.imu,
       "--poses",
       files.imu,
       "--out",
       dir.File("out"),
       "--bias-model",
       "wiggly"},
  };
  const std::vector<std::string> messages = {
      "do not overlap",
      "imu.yaml:1: a YAML file ('%YAML:1.0'), not a table of numbers: IMU noise densities "
      "(Kalibr's imu.yaml) go to --imu-yaml",
      "--poses is required",
      "--bias-model"};
  for (size_t c = 0; c < cases.size(); ++c) {
    const auto result = RunTool(cases[c]);
    EXPECT_EQ(result.exit_code, 2) << result.err;
    EXPECT_EQ(CountLines(result.err), 1) << result.err;
    EXPECT_THAT(result.err, HasSubstr(messages[c]));
    EXPECT_FALSE(std::filesystem::exists(dir.File("out/result.yaml")));
  }
}

}  // namespace
}  // namespace splinecal
