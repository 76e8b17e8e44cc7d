// `splinecal fit` end to end: the binary on simulated files, and the EuRoC excerpt.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "calib/fit_test_data.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/spline/trajectory_model.h"
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

// `splinecal fit` on `files` at 0.1 s knots into dir/out, with `extra` flags.
testing::ToolResult RunFit(const TempDir& dir,
                           const Files& files,
                           const std::vector<std::string>& extra = {}) {
  std::vector<std::string> args = {
      "fit", "--imu", files.imu, "--poses", files.poses, "--out", dir.File("out")};
  args.push_back("--knot-spacing");
  args.push_back("0.1");
  args.insert(args.end(), extra.begin(), extra.end());
  return RunTool(args);
}

// result.yaml's estimate `key` within 3 of its reported `key`_std of `truth`, per axis.
void ExpectWithinThreeStds(const YAML::Node& yaml,
                           const std::string& key,
                           const Eigen::Vector3d& truth) {
  for (int a = 0; a < 3; ++a) {
    EXPECT_NEAR(yaml[key][a].as<double>(), truth[a], 3.0 * yaml[key + "_std"][a].as<double>())
        << key << " axis " << a;
  }
}

TEST(FitCommand, WritesEveryOutputAndTheEstimates) {
  TempDir dir;
  FitScenario scenario;
  scenario.duration_s = 8.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  const FitData data = MakeFitData(scenario);
  const Files files = WriteScenario(dir, data);
  const auto result = RunFit(dir, files);
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
  ExpectWithinThreeStds(yaml, "gyro_bias", scenario.gyro_bias);
  EXPECT_EQ(CountLines(ReadFileText(dir.File("out/residuals.csv"))),
            1 + static_cast<int>(data.imu.size()));
  // The model line, the header and a row per control pose.
  EXPECT_EQ(CountLines(ReadFileText(dir.File("out/spline.csv"))),
            2 + data.truth.num_control_poses());
  EXPECT_EQ(yaml["trajectory"].as<std::string>(), "se3");
  const std::string html = ReadFileText(dir.File("out/report.html"));
  EXPECT_THAT(html, HasSubstr("<svg"));
  EXPECT_THAT(html, HasSubstr("Residuals"));
  EXPECT_TRUE(std::filesystem::exists(dir.File("out/pose_residuals.csv")));
}

// --trajectory split end to end: simulated from a split truth spline, the fit reports the model,
// writes it into spline.csv, and that file read back (as `evaluate` reads it) follows the truth.
TEST(FitCommand, SplitTrajectoryIsFittedWrittenAndReadBack) {
  TempDir dir;
  FitScenario scenario;
  scenario.truth_model = TrajectoryModel::kSplitSO3R3;
  scenario.duration_s = 8.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  const FitData data = MakeFitData(scenario);
  const Files files = WriteScenario(dir, data);
  const auto result = RunFit(dir, files, {"--trajectory", "split", "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const YAML::Node yaml = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
  EXPECT_EQ(yaml["trajectory"].as<std::string>(), "split");
  ExpectWithinThreeStds(yaml, "gyro_bias", scenario.gyro_bias);
  ExpectWithinThreeStds(yaml, "accel_bias", scenario.accel_bias);
  const SE3Splined fitted = ReadSplineCsv(dir.File("out/spline.csv"));
  ASSERT_EQ(fitted.model(), TrajectoryModel::kSplitSO3R3);
  EXPECT_THAT(ReadFileText(dir.File("out/report.html")), HasSubstr("split"));
  // The poses carry 1 mm and 1 mrad of noise per axis (FitScenario) and the fit averages ~10 of
  // them per knot interval with the IMU: nowhere on the valid range, ends included, may it be
  // further from the truth than 3 standard deviations of one pose, 3 sqrt(3) sigma in norm
  // (measured: 0.96 mm and 0.53 mrad at the worst time).
  const double bound_m = 3.0 * std::sqrt(3.0) * scenario.pose_sigma_m;
  const double bound_rad = 3.0 * std::sqrt(3.0) * scenario.pose_sigma_rad;
  double worst_m = 0.0;
  double worst_rad = 0.0;
  const int64_t start_ns = std::max(fitted.start_time_ns(), data.truth.start_time_ns());
  const int64_t end_ns = std::min(fitted.end_time_ns(), data.truth.end_time_ns());
  for (int64_t t = start_ns; t <= end_ns; t += 10'000'000) {
    const SE3d error = data.truth.PoseNs(t).inverse() * fitted.PoseNs(t);
    worst_m = std::max(worst_m, error.translation().norm());
    worst_rad = std::max(worst_rad, error.so3().Log().norm());
  }
  std::printf("split fit vs truth: max %.3f mm, %.3f mrad\n", 1e3 * worst_m, 1e3 * worst_rad);
  EXPECT_LT(worst_m, bound_m);
  EXPECT_LT(worst_rad, bound_rad);
}

TEST(FitCommand, QuietSilencesProgress) {
  TempDir dir;
  FitScenario scenario;
  scenario.duration_s = 5.0;
  const Files files = WriteScenario(dir, MakeFitData(scenario));
  const auto result = RunFit(dir, files, {"--quiet"});
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
