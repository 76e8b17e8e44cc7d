#include "splinecal/report/simulate_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <regex>
#include <set>
#include <string>
#include <vector>

#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::StartsWith;

constexpr int64_t kKnotSpacingNs = 50'000'000;

// A 1 s noise-free run on the vio_course spline.
SimulationRun SmallRun() {
  SimulationRun run;
  SimulationTrajectory trajectory;
  trajectory.name = "vio_course";
  run.start_ns = kKnotSpacingNs;
  run.end_ns = run.start_ns + 1'000'000'000;
  run.knot_spacing_s = 0.05;
  run.spline = FitSimulationTrajectory(trajectory, run.start_ns, run.end_ns, kKnotSpacingNs);
  run.options.seed = 7;
  run.options.gyro_bias = Eigen::Vector3d(1e-3, 0.0, 0.0);
  SimulateImu(
      run.spline.fit.MakeSpline(), run.start_ns, run.end_ns, run.options, &run.imu, &run.truth);
  return run;
}

TEST(SimulationResultYaml, EveryKeyOnceWithTheRunsFigures) {
  const SimulationRun run = SmallRun();
  const std::string text = SimulationResultYaml(run);
  EXPECT_THAT(text, StartsWith("# splinecal simulate: "));
  std::vector<std::string> keys;
  const std::regex key("^([A-Za-z_0-9]+):", std::regex::multiline);
  for (auto it = std::sregex_iterator(text.begin(), text.end(), key); it != std::sregex_iterator();
       ++it) {
    keys.push_back((*it)[1]);
  }
  const std::set<std::string> unique(keys.begin(), keys.end());
  EXPECT_EQ(unique.size(), keys.size()) << text;
  EXPECT_EQ(unique,
            (std::set<std::string>{"trajectory",
                                   "start_t_ns",
                                   "end_t_ns",
                                   "duration_s",
                                   "imu_rate_hz",
                                   "num_imu_samples",
                                   "seed",
                                   "gravity_m_s2",
                                   "gravity_w",
                                   "noise_free",
                                   "noise",
                                   "initial_gyro_bias",
                                   "initial_accel_bias",
                                   "final_gyro_bias",
                                   "final_accel_bias",
                                   "spline"}));

  const YAML::Node yaml = testing::LoadStrictYaml(text);
  EXPECT_EQ(yaml["trajectory"].as<std::string>(), "vio_course");
  EXPECT_EQ(yaml["start_t_ns"].as<int64_t>(), run.start_ns);
  EXPECT_DOUBLE_EQ(yaml["duration_s"].as<double>(), 1.0);
  EXPECT_EQ(yaml["num_imu_samples"].as<size_t>(), run.imu.size());
  EXPECT_EQ(yaml["seed"].as<int64_t>(), 7);
  EXPECT_EQ(yaml["spline"]["num_control_poses"].as<size_t>(), run.spline.fit.control_poses.size());
  EXPECT_EQ(yaml["spline"]["t0_ns"].as<int64_t>(), run.spline.fit.layout.t0_ns);
  EXPECT_DOUBLE_EQ(yaml["spline"]["knot_spacing_s"].as<double>(), 0.05);
  EXPECT_EQ(yaml["noise"].size(), 4u);
  EXPECT_FALSE(yaml["cameras"]);  // no camchain, no camera truth
}

}  // namespace
}  // namespace splinecal
