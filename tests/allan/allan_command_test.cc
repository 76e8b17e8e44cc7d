// `splinecal allan` end to end: the binary, its files, its exit codes (docs/conventions.md,
// "Command line": bad input exits 2 with one line naming the file and line, nothing written).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/allan/allan_deviation.h"
#include "splinecal/allan/work_budget.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/static_recording.h"
#include "splinecal/units.h"
#include "testing/run_tool.h"
#include "testing/shared_data.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::RefusedInOneLine;
using testing::RunTool;
using ::testing::StartsWith;
using testing::TempDir;

// A static EuRoC file: ADIS16448-like white noise and bias random walk on six axes; with
// bump_at_row >= 0, one second of rotation at 0.5 rad/s about x from that row on.
std::string WriteStaticEuroc(const TempDir& dir,
                             const std::string& name,
                             int rows,
                             int bump_at_row = -1) {
  std::mt19937_64 engine(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double rate = 200.0;
  const double white[6] = {1.6968e-4, 1.6968e-4, 1.6968e-4, 2e-3, 2e-3, 2e-3};
  const double walk[6] = {1.9393e-5, 1.9393e-5, 1.9393e-5, 3e-3, 3e-3, 3e-3};
  double bias[6] = {0.01, -0.02, 0.0, 0.1, 0.0, 9.81};
  std::vector<ImuSample> samples(rows);
  for (int k = 0; k < rows; ++k) {
    double y[6];
    for (int a = 0; a < 6; ++a) {
      bias[a] += walk[a] / std::sqrt(rate) * normal(engine);
      y[a] = bias[a] + white[a] * std::sqrt(rate) * normal(engine);
    }
    if (bump_at_row >= 0 && k >= bump_at_row && k < bump_at_row + 200) y[0] += 0.5;
    samples[k].t_ns = 1403636579758555392LL + 5000000LL * k;
    samples[k].gyro = Eigen::Vector3d(y[0], y[1], y[2]);
    samples[k].accel = Eigen::Vector3d(y[3], y[4], y[5]);
  }
  std::ostringstream text;
  WriteEurocImu(samples, &text);
  return dir.Write(name, text.str());
}

// allan.csv as named columns of numbers.
std::map<std::string, std::vector<double>> ReadAllanCsv(const std::string& path) {
  std::istringstream text(testing::ReadFileText(path));
  std::string line;
  std::getline(text, line);
  std::vector<std::string> names;
  std::istringstream header(line.substr(1));  // after '#'
  for (std::string name; std::getline(header, name, ',');) names.push_back(name);
  std::map<std::string, std::vector<double>> columns;
  while (std::getline(text, line)) {
    std::istringstream row(line);
    std::string field;
    for (size_t i = 0; std::getline(row, field, ','); ++i) {
      columns[names.at(i)].push_back(std::stod(field));
    }
  }
  return columns;
}

TEST(AllanCommand, WritesItsFourFiles) {
  TempDir dir;
  const std::string imu = WriteStaticEuroc(dir, "imu0.csv", 200 * 600);
  const testing::ToolResult run = RunTool({"allan", "--imu", imu, "--out", dir.File("out")});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  for (const char* file : {"allan.csv", "imu.yaml", "result.yaml", "allan.svg"}) {
    EXPECT_TRUE(std::filesystem::exists(dir.File("out/") + file)) << file;
  }
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(dir.File("out")), 2);  // imu.yaml, result.yaml
  const YAML::Node imu_yaml = testing::LoadStrictYamlFile(dir.File("out/imu.yaml"));
  EXPECT_NEAR(imu_yaml["gyroscope_noise_density"].as<double>() / 1.6968e-4, 1.0, 0.05);
  EXPECT_NEAR(imu_yaml["accelerometer_noise_density"].as<double>() / 2e-3, 1.0, 0.05);
  EXPECT_DOUBLE_EQ(imu_yaml["update_rate"].as<double>(), 200.0);
  EXPECT_THAT(testing::ReadFileText(dir.File("out/allan.csv")), StartsWith("#tau_s,gyro_x,"));
  EXPECT_THAT(run.err, HasSubstr("gyroscope_noise_density"));
}

TEST(AllanCommand, PlainColumnsOfOneSensor) {
  TempDir dir;
  std::mt19937_64 engine(3);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::string text;
  for (int k = 0; k < 20000; ++k) {
    // deg/s, converted with --gyro-scale.
    text += std::to_string(0.5 + 0.1 * normal(engine)) + " " +
            std::to_string(0.1 * normal(engine)) + "\n";
  }
  const std::string columns = dir.Write("gyro.txt", text);
  const testing::ToolResult run = RunTool({"allan",
                                           "--columns",
                                           columns,
                                           "--rate",
                                           "100",
                                           "--sensor",
                                           "gyro",
                                           "--gyro-scale",
                                           "0.017453292519943295",
                                           "--out",
                                           dir.File("out"),
                                           "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(run.err, "");
  const YAML::Node result = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
  // White noise of 0.1 deg/s per sample at 100 Hz: N = 0.1 * pi / 180 / sqrt(100).
  EXPECT_NEAR(result["gyroscope"]["x"]["noise_density"].as<double>() / (0.1 * kPi / 180.0 / 10.0),
              1.0,
              0.05);
  EXPECT_FALSE(result["accelerometer"]);
  EXPECT_THAT(
      testing::ReadFileText(dir.File("out/allan.csv")),
      StartsWith("#tau_s,gyro_x,gyro_y,gyro_x_low,gyro_y_low,gyro_x_high,gyro_y_high,stride,"
                 "terms\n"));
}

TEST(AllanCommand, BadInputExitsTwoWithOneLineAndNoFiles) {
  TempDir dir;
  const std::string header =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  std::string nan_file = header;
  for (int k = 0; k < 100; ++k) {
    nan_file += std::to_string(1000000 + 5000000LL * k) +
                (k == 41 ? ",0,NaN,0,0,0,9.8\n" : ",0.1,0,0,0,0,9.8\n");
  }
  std::string constant_file = header;
  for (int k = 0; k < 100; ++k) {
    constant_file += std::to_string(1000000 + 5000000LL * k) + ",0.25," +
                     std::to_string(0.001 * (k % 7)) + ",0,0,0,9.8\n";
  }
  std::string short_file = header;
  for (int k = 0; k < 20; ++k) {
    short_file +=
        std::to_string(1000000 + 5000000LL * k) + ",0," + std::to_string(k % 3) + ",0,0,0,9.8\n";
  }
  const std::string out = dir.File("out");
  const std::vector<testing::BadInvocation> cases = {
      {{"--imu", dir.Write("nan.csv", nan_file)}, "nan.csv:43:"},
      {{"--imu", dir.Write("constant.csv", constant_file)},
       "constant.csv: gyro_x: all 100 samples are equal"},
      {{"--imu", dir.Write("short.csv", short_file)},
       "short.csv: too few samples for the averaging times: 20 samples"},
      {{"--imu", dir.File("missing.csv")}, "missing.csv"},
      {{"--columns", dir.Write("c.txt", "1\n2\n")}, "--rate"},
      {{"--imu", dir.File("nan.csv"), "--combine", "median"}, "--combine"},
      {{"--imu", dir.File("nan.csv"), "--max-tau-fraction", "0.7"}, "max tau fraction"},
      {{"--imu", dir.File("nan.csv"), "--max-passes", "-1"}, "--max-passes"},
  };
  // --quiet: progress lines aside, the error is the one line on stderr.
  testing::ExpectEachRefusedWritingNothing(
      {"allan", "--quiet", "--out", out}, cases, out + "/result.yaml");
}

// 1000 averaging times per decade: within the default budget of 100 passes, the short ones
// strided, allan.csv and result.yaml say which start indices each used.
TEST(AllanCommand, ThousandTausPerDecadeStrideWithinTheBudget) {
  TempDir dir;
  constexpr int kRows = 200 * 600;
  const std::string imu = WriteStaticEuroc(dir, "imu0.csv", kRows);
  const testing::ToolResult run =
      RunTool({"allan", "--imu", imu, "--out", dir.File("out"), "--taus-per-decade", "1000"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("use every s-th start index"));
  const auto csv = ReadAllanCsv(dir.File("out/allan.csv"));
  const std::vector<int64_t> sizes = AllanClusterSizes(kRows, 1000, 0.1);
  ASSERT_EQ(csv.at("tau_s").size(), sizes.size());
  double terms = 0.0;
  int strided = 0;
  for (size_t i = 0; i < sizes.size(); ++i) {
    const int64_t stride = static_cast<int64_t>(csv.at("stride")[i]);
    EXPECT_EQ(csv.at("terms")[i], static_cast<double>(AllanTermCount(kRows, sizes[i], stride)))
        << i;
    terms += csv.at("terms")[i];
    strided += stride > 1;
    EXPECT_GT(csv.at("gyro_x")[i], 0.0);
    EXPECT_LT(csv.at("gyro_x_low")[i], csv.at("gyro_x")[i]);
  }
  EXPECT_LE(terms, 100.0 * kRows);
  EXPECT_GT(strided, 0);
  const YAML::Node result = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
  EXPECT_EQ(result["max_passes"].as<int>(), 100);
  EXPECT_EQ(result["strided_averaging_times"].as<int>(), strided);
  EXPECT_DOUBLE_EQ(result["passes_used"].as<double>(), terms / kRows);
  // The white noise, read off the densest curve, still within the usual 5%.
  EXPECT_NEAR(result["gyroscope_noise_density"].as<double>() / 1.6968e-4, 1.0, 0.05);
}

// --max-passes 0: no budget, the fully overlapping curve at every averaging time, bit for bit the
// library's OverlappingAllanDeviation of the same samples.
TEST(AllanCommand, MaxPassesZeroGivesTheExactCurve) {
  TempDir dir;
  constexpr int kRows = 200 * 600;
  const std::string imu = WriteStaticEuroc(dir, "imu0.csv", kRows);
  const testing::ToolResult run = RunTool({"allan",
                                           "--imu",
                                           imu,
                                           "--out",
                                           dir.File("out"),
                                           "--taus-per-decade",
                                           "1000",
                                           "--max-passes",
                                           "0",
                                           "--quiet"});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  const auto csv = ReadAllanCsv(dir.File("out/allan.csv"));
  const std::vector<int64_t> sizes = AllanClusterSizes(kRows, 1000, 0.1);
  StaticRecording recording = ReadEurocStaticRecording(imu);
  for (const AxisSeries& axis : recording.axes) {
    const AllanCurve exact =
        OverlappingAllanDeviation(axis.samples, recording.rate_hz, sizes, axis.name());
    EXPECT_EQ(csv.at(axis.name()), exact.adev) << axis.name();
  }
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(csv.at("stride")[i], 1.0);
    EXPECT_EQ(csv.at("terms")[i], static_cast<double>(kRows - 2 * sizes[i] + 1));
  }
  const YAML::Node result = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
  EXPECT_EQ(result["max_passes"].as<int>(), 0);
  EXPECT_EQ(result["strided_averaging_times"].as<int>(), 0);
}

// Real recordings that move all the time: the EuRoC calibration sequence (waved in front of the
// target) and V1_01_easy (a flight). Refused, with one line naming the file and what moves; with
// --allow-motion every key is marked unreliable, and no identified value exceeds its own bound
// (the earlier fit reported a gyro random walk 40,000 times the sensor's, above its own bound).
TEST(AllanCommand, RealRecordingsThatMoveAreRefused) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/imu0.csv");
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_v1_01_easy/imu0.csv");
  for (const char* file : {"euroc_imu_april/imu0.csv", "euroc_v1_01_easy/imu0.csv"}) {
    SCOPED_TRACE(file);
    TempDir dir;
    const std::string imu = testing::SharedDataPath(file);
    const testing::ToolResult refused =
        RunTool({"allan", "--imu", imu, "--out", dir.File("out"), "--quiet"});
    EXPECT_TRUE(RefusedInOneLine(refused, std::string(file) + ": the recording is not static: "));
    EXPECT_THAT(refused.err, HasSubstr("--allow-motion"));
    EXPECT_FALSE(std::filesystem::exists(dir.File("out/result.yaml")));

    const testing::ToolResult allowed =
        RunTool({"allan", "--imu", imu, "--out", dir.File("out"), "--allow-motion"});
    ASSERT_EQ(allowed.exit_code, 0) << allowed.err;
    EXPECT_THAT(allowed.err, HasSubstr("UNRELIABLE"));
    const YAML::Node result = testing::LoadStrictYamlFile(dir.File("out/result.yaml"));
    EXPECT_TRUE(result["motion_detected"].as<bool>());
    EXPECT_TRUE(result["gyroscope_random_walk_unreliable"].as<bool>());
    for (const char* sensor : {"gyroscope", "accelerometer"}) {
      for (const char* axis : {"x", "y", "z"}) {
        const YAML::Node node = result[sensor][axis];
        EXPECT_EQ(node["unreliable"].as<std::string>(), "the recording moves");
        for (const char* term :
             {"quantization", "noise_density", "bias_instability", "random_walk", "rate_ramp"}) {
          if (node[term].as<std::string>() == "not identified") continue;
          EXPECT_LE(node[term].as<double>(), node[std::string(term) + "_upper_bound"].as<double>())
              << sensor << " " << axis << " " << term;
        }
      }
    }
    EXPECT_THAT(testing::ReadFileText(dir.File("out/imu.yaml")),
                HasSubstr("UNRELIABLE: the recording moves"));
  }
}

// A static recording that someone bumps after 30 s: refused, naming the time; --start cuts the
// static stretch after it out of the log, --end one before it.
TEST(AllanCommand, StartAndEndCutAStaticStretch) {
  TempDir dir;
  const std::string imu = WriteStaticEuroc(dir, "bumped.csv", 200 * 300, 200 * 30);
  const testing::ToolResult refused =
      RunTool({"allan", "--imu", imu, "--out", dir.File("out"), "--quiet"});
  EXPECT_EQ(refused.exit_code, 2) << refused.err;
  EXPECT_THAT(refused.err, HasSubstr("gyro_x"));
  EXPECT_THAT(refused.err, HasSubstr("the first at t = 30.0 s"));

  const testing::ToolResult after =
      RunTool({"allan", "--imu", imu, "--start", "40", "--out", dir.File("after"), "--quiet"});
  ASSERT_EQ(after.exit_code, 0) << after.err;
  const YAML::Node result = testing::LoadStrictYamlFile(dir.File("after/result.yaml"));
  EXPECT_DOUBLE_EQ(result["start_s"].as<double>(), 40.0);
  EXPECT_DOUBLE_EQ(result["end_s"].as<double>(), 300.0);
  EXPECT_EQ(result["num_samples"].as<int>(), 200 * 260);
  EXPECT_FALSE(result["motion_detected"].as<bool>());
  EXPECT_NEAR(result["gyroscope_noise_density"].as<double>() / 1.6968e-4, 1.0, 0.05);

  const testing::ToolResult before =
      RunTool({"allan", "--imu", imu, "--end", "29.5", "--out", dir.File("before"), "--quiet"});
  ASSERT_EQ(before.exit_code, 0) << before.err;
  EXPECT_EQ(testing::LoadStrictYamlFile(dir.File("before/result.yaml"))["num_samples"].as<int>(),
            5900);

  for (const std::vector<std::string>& flags :
       {std::vector<std::string>{"--start", "400"},
        std::vector<std::string>{"--start", "50", "--end", "20"}}) {
    std::vector<std::string> args = {"allan", "--imu", imu, "--out", dir.File("bad"), "--quiet"};
    args.insert(args.end(), flags.begin(), flags.end());
    const testing::ToolResult run = RunTool(args);
    EXPECT_TRUE(RefusedInOneLine(run, "--start"));
    EXPECT_FALSE(std::filesystem::exists(dir.File("bad/result.yaml")));
  }
}

}  // namespace
}  // namespace splinecal
