// `splinecal integrate` end to end: simulated files (written with the library), the EuRoC data,
// and bad input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/imu/integrate.h"
#include "splinecal/io/euroc.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "testing/paths.h"
#include "testing/run_tool.h"
#include "testing/shared_data.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RunTool;
using testing::TempDir;

struct Files {
  std::string imu;
  std::string truth;
};

// Noise-free vio_course, 20 s at 200 Hz, written as EuRoC files.
Files WriteCourse(const TempDir& dir) {
  const int64_t start_ns = 50'000'000;
  const int64_t end_ns = start_ns + 20'000'000'000;
  const SE3Splined spline =
      FitAnalyticTrajectory(VioCourseTrajectory(), start_ns, end_ns, 50'000'000).MakeSpline();
  SimulationOptions options;
  options.noise_free = true;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
  SimulateImu(spline, start_ns, end_ns, options, &imu, &truth);
  std::ostringstream imu_csv, truth_csv;
  WriteEurocImu(imu, &imu_csv);
  WriteEurocGroundTruth(truth, &truth_csv);
  return {dir.Write("imu0.csv", imu_csv.str()), dir.Write("gt.csv", truth_csv.str())};
}

TEST(IntegrateCommand, MidpointBeatsEulerTenfoldAndRk4BeatsMidpoint) {
  TempDir dir;
  const Files files = WriteCourse(dir);
  const std::string out = dir.File("out");
  const auto result = RunTool(
      {"integrate", "--imu", files.imu, "--groundtruth", files.truth, "--out", out, "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("midpoint"));  // The drift table.
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 1);
  const YAML::Node yaml = testing::LoadStrictYamlFile(out + "/result.yaml");
  const double euler = yaml["euler"]["final_position_error_m"].as<double>();
  const double midpoint = yaml["midpoint"]["final_position_error_m"].as<double>();
  const double rk4 = yaml["rk4"]["final_position_error_m"].as<double>();
  EXPECT_LE(midpoint, euler / 10.0);
  EXPECT_LE(rk4, midpoint);
  EXPECT_GT(yaml["euler"]["ate_rmse_m"].as<double>(), 0.0);
  EXPECT_EQ(yaml["euler"]["num_compared"].as<int>(), 4001);
  for (const char* method : {"euler", "midpoint", "rk4"}) {
    const std::vector<GroundTruthState> rows =
        ReadEurocGroundTruth(out + "/trajectory_" + std::string(method) + ".csv");
    EXPECT_EQ(rows.size(), 4001u) << method;
  }
  const std::string svg = ReadFileText(out + "/trajectory.svg");
  EXPECT_THAT(svg, HasSubstr("<svg"));
  EXPECT_THAT(svg, HasSubstr("ground truth"));
}

TEST(IntegrateCommand, StartDurationAndMethodSelectAWindow) {
  TempDir dir;
  const Files files = WriteCourse(dir);
  const std::string out = dir.File("out");
  const auto result = RunTool({"integrate",
                               "--imu",
                               files.imu,
                               "--groundtruth",
                               files.truth,
                               "--method",
                               "midpoint",
                               "--start",
                               "5",
                               "--duration",
                               "2",
                               "--out",
                               out,
                               "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const YAML::Node yaml = testing::LoadStrictYamlFile(out + "/result.yaml");
  EXPECT_EQ(yaml["start_t_ns"].as<int64_t>(), 5'050'000'000);
  EXPECT_EQ(yaml["end_t_ns"].as<int64_t>(), 7'050'000'000);
  EXPECT_FALSE(yaml["euler"]);
  EXPECT_EQ(yaml["midpoint"]["num_compared"].as<int>(), 401);
  EXPECT_FALSE(std::filesystem::exists(out + "/trajectory_euler.csv"));
}

TEST(IntegrateCommand, BadInputExitsTwoWithOneLineAndNoOutput) {
  TempDir dir;
  const Files files = WriteCourse(dir);
  // The same IMU in units of g, and with a row out of order.
  std::vector<ImuSample> imu = ReadEurocImu(files.imu);
  std::vector<ImuSample> in_g = imu;
  for (ImuSample& s : in_g) s.accel /= 9.81;
  std::ostringstream g_csv;
  WriteEurocImu(in_g, &g_csv);
  const std::string g_file = dir.Write("imu_g.csv", g_csv.str());
  std::string text = ReadFileText(files.imu);
  const size_t line3 = text.find('\n', text.find('\n', text.find('\n') + 1) + 1) + 1;
  const size_t line4 = text.find('\n', line3) + 1;
  const size_t line5 = text.find('\n', line4) + 1;
  const std::string swapped = text.substr(0, line3) + text.substr(line4, line5 - line4) +
                              text.substr(line3, line4 - line3) + text.substr(line5);
  const std::string unsorted = dir.Write("imu_unsorted.csv", swapped);
  const std::string out = dir.File("out");
  const std::vector<testing::BadInvocation> cases = {
      {{"--imu", files.imu, "--groundtruth", files.truth, "--start", "500"}, "--start"},
      {{"--imu", files.imu, "--groundtruth", files.truth, "--duration", "500"}, "--duration"},
      {{"--imu", files.imu, "--groundtruth", files.truth, "--method", "heun"}, "heun"},
      {{"--imu", g_file, "--groundtruth", files.truth}, "--accel-unit g"},
      {{"--imu", unsorted, "--groundtruth", files.truth}, "imu_unsorted.csv:"},
      {{"--imu", files.imu}, "--groundtruth"},
      {{"--imu", files.imu, "--groundtruth", files.imu}, "imu0.csv:"},
  };
  testing::ExpectEachRefusedWritingNothing(
      {"integrate", "--out", out}, cases, out + "/result.yaml");
  // With --accel-unit g the same file integrates.
  const auto result = RunTool({"integrate",
                               "--imu",
                               g_file,
                               "--groundtruth",
                               files.truth,
                               "--accel-unit",
                               "g",
                               "--duration",
                               "1",
                               "--out",
                               out,
                               "--quiet"});
  EXPECT_EQ(result.exit_code, 0) << result.err;
}

// Real data: EuRoC V1_01_easy, first 10 s. The numbers go to docs/integrate.md. What they should
// be is checked against the data in tests/imu/integrate_test.cc (IntegrateImu.
// EurocV101EasyFirstTenSeconds); here the command must report exactly what the library computes
// from the same files, start row and gravity: the same code on the same doubles, written with 17
// significant digits, so the tolerance is a few ulp (1e-12 relative). A command that did not
// move, or integrated from another start, would be off by metres.
TEST(IntegrateCommand, EurocV101EasyFirstTenSecondsReportsTheLibrarysDrift) {
  const std::string data = testing::SharedDataDir() + "/euroc_v1_01_easy";
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_v1_01_easy/imu0.csv");
  TempDir dir;
  const auto result = RunTool({"integrate",
                               "--imu",
                               data + "/imu0.csv",
                               "--groundtruth",
                               data + "/groundtruth.csv",
                               "--duration",
                               "10",
                               "--out",
                               dir.File("out"),
                               "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  std::printf("%s", result.out.c_str());
  const YAML::Node yaml = testing::LoadStrictYamlFile(dir.File("out") + "/result.yaml");
  EXPECT_NEAR(yaml["duration_s"].as<double>(), 10.0, 1e-9);

  const std::vector<ImuSample> imu = ReadEurocImu(data + "/imu0.csv");
  const std::vector<GroundTruthState> truth = ReadEurocGroundTruth(data + "/groundtruth.csv");
  const NavState start = NavStateFromGroundTruth(truth.front());
  const int64_t end_ns = start.t_ns + 10'000'000'000;
  EXPECT_EQ(yaml["start_t_ns"].as<int64_t>(), start.t_ns);
  EXPECT_EQ(yaml["end_t_ns"].as<int64_t>(), end_ns);
  constexpr double kRelativeTolerance = 1e-12;
  for (IntegrationMethod method :
       {IntegrationMethod::kEuler, IntegrationMethod::kMidpoint, IntegrationMethod::kRk4}) {
    std::vector<NavState> trajectory;
    IntegrateImu(imu,
                 start,
                 end_ns,
                 BiasFromGroundTruth(truth.front()),
                 Eigen::Vector3d(0.0, 0.0, -9.81),
                 method,
                 &trajectory);
    const DriftMetrics drift = ComputeDrift(trajectory, truth);
    const YAML::Node reported = yaml[IntegrationMethodName(method)];
    const auto expect_same = [&](const char* key, double expected) {
      EXPECT_NEAR(reported[key].as<double>(), expected, kRelativeTolerance * expected)
          << IntegrationMethodName(method) << " " << key;
    };
    expect_same("final_position_error_m", drift.final_position_error_m);
    expect_same("final_rotation_error_deg", drift.final_rotation_error_deg);
    expect_same("ate_rmse_m", drift.ate_rmse_m);
    EXPECT_EQ(reported["num_compared"].as<int64_t>(), drift.num_compared);
  }
}

}  // namespace
}  // namespace splinecal
