// The seed's experiment [seed000 (1)] through the command line (label "slow": four 2-hour EuRoC
// files of 1.44 million rows are written and read): the ADIS16448's white noise and bias random
// walk scaled 1x, 10x, 100x and 1000x, gravity and the offsets not. The recovered/true ratios must
// be the same at every scale (the method is scale-invariant; only the text's rounding differs)
// and K identified at every scale.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "splinecal/io/euroc.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

using testing::RunTool;
using testing::TempDir;

constexpr double kRateHz = 200.0;
constexpr int kRows = static_cast<int>(2 * 3600 * kRateHz);
// EuRoC's ADIS16448 (its sensor.yaml): gyro N, K; accel N, K.
constexpr double kTrue[4] = {1.6968e-4, 1.9393e-5, 2.0e-3, 3.0e-3};
const char* const kKeys[4] = {"gyroscope_noise_density",
                              "gyroscope_random_walk",
                              "accelerometer_noise_density",
                              "accelerometer_random_walk"};
// Scaling the noise scales every estimate; the decisions use ratios only. What differs between
// scales is the text's rounding to 17 digits of offset + noise: 1e-15 of gravity against noise of
// 3e-2 per sample, far below this bar.
constexpr double kScaleInvarianceTolerance = 1e-9;

// The same unit draws at every scale, written as offset + scale * (bias walk + white noise).
std::string WriteScaled(const TempDir& dir, double scale) {
  std::mt19937_64 engine(2024);
  std::normal_distribution<double> normal(0.0, 1.0);
  const double offset[6] = {0.01, -0.02, 0.003, 0.1, -0.2, 9.81};
  const double white[6] = {kTrue[0], kTrue[0], kTrue[0], kTrue[2], kTrue[2], kTrue[2]};
  const double walk[6] = {kTrue[1], kTrue[1], kTrue[1], kTrue[3], kTrue[3], kTrue[3]};
  double bias[6] = {0, 0, 0, 0, 0, 0};
  const std::string path = dir.File("scale" + std::to_string(static_cast<int>(scale)) + ".csv");
  std::vector<ImuSample> samples(kRows);
  for (int k = 0; k < kRows; ++k) {
    double y[6];
    for (int a = 0; a < 6; ++a) {
      bias[a] += walk[a] / std::sqrt(kRateHz) * normal(engine);
      y[a] = offset[a] + scale * (bias[a] + white[a] * std::sqrt(kRateHz) * normal(engine));
    }
    samples[k].t_ns = 1403636579758555392LL + 5000000LL * k;
    samples[k].gyro = Eigen::Vector3d(y[0], y[1], y[2]);
    samples[k].accel = Eigen::Vector3d(y[3], y[4], y[5]);
  }
  std::ofstream file(path);
  WriteEurocImu(samples, &file);
  return path;
}

TEST(AllanCommandSeedExperiment, RatiosEqualAcrossNoiseScales) {
  TempDir dir;
  std::vector<double> base_ratios;
  for (const double scale : {1.0, 10.0, 100.0, 1000.0}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    const std::string imu = WriteScaled(dir, scale);
    const std::string out = dir.File("out" + std::to_string(static_cast<int>(scale)));
    const testing::ToolResult run = RunTool({"allan", "--imu", imu, "--out", out, "--quiet"});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    const YAML::Node result = testing::LoadStrictYamlFile(out + "/result.yaml");
    EXPECT_FALSE(result["motion_detected"].as<bool>());
    std::vector<double> ratios;
    for (int key = 0; key < 4; ++key) {
      EXPECT_FALSE(result[std::string(kKeys[key]) + "_is_upper_bound"].as<bool>()) << kKeys[key];
      ratios.push_back(result[kKeys[key]].as<double>() / (scale * kTrue[key]));
      std::printf("scale %4.0f  %-28s ratio %.12f (axes %s)\n",
                  scale,
                  kKeys[key],
                  ratios.back(),
                  result[std::string(kKeys[key]) + "_axes"].as<std::string>().c_str());
    }
    for (const char* sensor : {"gyroscope", "accelerometer"}) {
      for (const char* axis : {"x", "y", "z"}) {
        EXPECT_NE(result[sensor][axis]["random_walk"].as<std::string>(), "not identified")
            << sensor << " " << axis << ": "
            << result[sensor][axis]["random_walk_reason"].as<std::string>("");
      }
    }
    // Accuracy of one 2-hour run: N to 3%, K to 15%.
    EXPECT_NEAR(ratios[0], 1.0, 0.03);
    EXPECT_NEAR(ratios[1], 1.0, 0.15);
    EXPECT_NEAR(ratios[2], 1.0, 0.03);
    EXPECT_NEAR(ratios[3], 1.0, 0.15);
    if (base_ratios.empty()) base_ratios = ratios;
    for (int key = 0; key < 4; ++key) {
      EXPECT_NEAR(ratios[key], base_ratios[key], kScaleInvarianceTolerance * base_ratios[key])
          << kKeys[key];
    }
  }
}

}  // namespace
}  // namespace splinecal
