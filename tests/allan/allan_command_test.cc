// `splinecal allan` end to end: the binary, its files, its exit codes (docs/conventions.md,
// "Command line": bad input exits 2 with one line naming the file and line, nothing written).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <random>
#include <string>

#include "splinecal/units.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using testing::CountLines;
using ::testing::HasSubstr;
using testing::RunTool;
using ::testing::StartsWith;
using testing::TempDir;

// A static EuRoC file: ADIS16448-like white noise and bias random walk on six axes.
std::string WriteStaticEuroc(const TempDir& dir, const std::string& name, int rows) {
  std::mt19937_64 engine(17);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double rate = 200.0;
  const double white[6] = {1.6968e-4, 1.6968e-4, 1.6968e-4, 2e-3, 2e-3, 2e-3};
  const double walk[6] = {1.9393e-5, 1.9393e-5, 1.9393e-5, 3e-3, 3e-3, 3e-3};
  double bias[6] = {0.01, -0.02, 0.0, 0.1, 0.0, 9.81};
  std::string text =
      "#timestamp [ns],w_RS_S_x [rad s^-1],w_RS_S_y [rad s^-1],w_RS_S_z [rad s^-1],"
      "a_RS_S_x [m s^-2],a_RS_S_y [m s^-2],a_RS_S_z [m s^-2]\n";
  char line[256];
  for (int k = 0; k < rows; ++k) {
    double y[6];
    for (int a = 0; a < 6; ++a) {
      bias[a] += walk[a] / std::sqrt(rate) * normal(engine);
      y[a] = bias[a] + white[a] * std::sqrt(rate) * normal(engine);
    }
    std::snprintf(line,
                  sizeof(line),
                  "%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g\n",
                  1403636579758555392LL + 5000000LL * k,
                  y[0],
                  y[1],
                  y[2],
                  y[3],
                  y[4],
                  y[5]);
    text += line;
  }
  return dir.Write(name, text);
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
  EXPECT_THAT(testing::ReadFileText(dir.File("out/allan.csv")),
              StartsWith("#tau_s,gyro_x,gyro_y,gyro_x_low,gyro_y_low,gyro_x_high,gyro_y_high\n"));
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
  struct Case {
    std::vector<std::string> args;
    std::string message;
  };
  const std::string out = dir.File("out");
  const std::vector<Case> cases = {
      {{"--imu", dir.Write("nan.csv", nan_file)}, "nan.csv:43:"},
      {{"--imu", dir.Write("constant.csv", constant_file)},
       "constant.csv: gyro_x: all 100 samples are equal"},
      {{"--imu", dir.Write("short.csv", short_file)},
       "short.csv: too few samples for the averaging times: 20 samples"},
      {{"--imu", dir.File("missing.csv")}, "missing.csv"},
      {{"--columns", dir.Write("c.txt", "1\n2\n")}, "--rate"},
      {{"--imu", dir.File("nan.csv"), "--combine", "median"}, "--combine"},
      {{"--imu", dir.File("nan.csv"), "--max-tau-fraction", "0.7"}, "max tau fraction"},
  };
  for (const Case& c : cases) {
    // --quiet: progress lines aside, the error is the one line on stderr.
    std::vector<std::string> args = {"allan", "--quiet", "--out", out};
    args.insert(args.end(), c.args.begin(), c.args.end());
    const testing::ToolResult run = RunTool(args);
    EXPECT_EQ(run.exit_code, 2) << c.message << ": " << run.err;
    EXPECT_THAT(run.err, HasSubstr(c.message));
    EXPECT_EQ(CountLines(run.err), 1) << run.err;
    EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml")) << c.message;
  }
}

}  // namespace
}  // namespace splinecal
