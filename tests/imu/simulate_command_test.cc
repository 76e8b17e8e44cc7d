// `splinecal simulate` end to end: the binary's files, read back with the io layer.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/imu/imu_model.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/sim/trajectories.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using testing::ReadFileText;
using testing::RunTool;
using testing::TempDir;

// A smooth recorded trajectory must come back "well under a millimetre" (docs/simulate.md): the fit
// to 100 Hz poses of vio_course is ~1e-6 m (calib/pose_fit_test.cc); 1e-4 m leaves room for the
// 17-digit text round trip and the knot placement of a file's own time base.
constexpr double kTrajectoryFileTolerance = 1e-4;

struct Outputs {
  std::string imu, truth, spline, imu_yaml, result;
};

Outputs OutputsIn(const std::string& dir) {
  return {dir + "/mav0/imu0/data.csv",
          dir + "/mav0/state_groundtruth_estimate0/data.csv",
          dir + "/spline.csv",
          dir + "/imu.yaml",
          dir + "/result.yaml"};
}

TEST(SimulateCommand, WritesEveryOutput) {
  TempDir dir;
  const std::string out = dir.File("sim");
  const auto result = RunTool({"simulate", "--duration", "2", "--out", out, "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_EQ(result.err, "");  // --quiet
  const Outputs files = OutputsIn(out);
  const std::vector<ImuSample> imu = ReadEurocImu(files.imu);
  const std::vector<GroundTruthState> truth = ReadEurocGroundTruth(files.truth);
  ASSERT_EQ(imu.size(), 401u);
  ASSERT_EQ(truth.size(), imu.size());
  EXPECT_EQ(imu[1].t_ns - imu[0].t_ns, 5'000'000);
  EXPECT_EQ(truth.front().t_ns, imu.front().t_ns);
  const SE3Splined spline = ReadSplineCsv(files.spline);
  EXPECT_EQ(spline.dt_ns(), 50'000'000);
  EXPECT_LE(spline.start_time_ns(), imu.front().t_ns);
  EXPECT_GE(spline.end_time_ns(), imu.back().t_ns);
  const ImuNoise noise = ReadImuYaml(files.imu_yaml);
  EXPECT_DOUBLE_EQ(noise.gyroscope_noise_density, 1.6968e-4);
  EXPECT_DOUBLE_EQ(noise.update_rate_hz, 200.0);
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 2);  // imu.yaml, result.yaml
  const YAML::Node yaml = testing::LoadStrictYamlFile(files.result);
  EXPECT_EQ(yaml["trajectory"].as<std::string>(), "vio_course");
  EXPECT_EQ(yaml["num_imu_samples"].as<int>(), 401);
  EXPECT_LT(yaml["spline"]["fit_position_rms_m"].as<double>(), 1e-5);
  EXPECT_LT(yaml["spline"]["fit_rotation_rms_deg"].as<double>(), 1e-4);
}

TEST(SimulateCommand, NoiseFreeZeroBiasFileIsExactlyTheSplinePrediction) {
  TempDir dir;
  const std::string out = dir.File("sim");
  const auto result = RunTool(
      {"simulate", "--trajectory", "figure8", "--duration", "3", "--noise-free", "--out", out});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const Outputs files = OutputsIn(out);
  // spline.csv and the IMU file carry 17 significant digits: both read back bit-exactly.
  const SE3Splined spline = ReadSplineCsv(files.spline);
  const std::vector<ImuSample> imu = ReadEurocImu(files.imu);
  const std::vector<GroundTruthState> truth = ReadEurocGroundTruth(files.truth);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (size_t k = 0; k < imu.size(); ++k) {
    const Segment<double> segment = spline.SegmentAtNs(imu[k].t_ns);
    Eigen::Vector3d gyro, accel, v_w;
    PredictImu(spline, segment, GravityWorld(9.81), zero, zero, &gyro, &accel);
    ASSERT_EQ(imu[k].gyro, gyro) << "row " << k;
    ASSERT_EQ(imu[k].accel, accel) << "row " << k;
    SE3d T_w_s;
    spline.Evaluate(segment, &T_w_s, nullptr, nullptr, &v_w, nullptr);
    ASSERT_LT((truth[k].v_w - v_w).norm(), 1e-12) << "row " << k;
    ASSERT_LT((truth[k].p_w_s - T_w_s.translation()).norm(), 1e-12) << "row " << k;
    ASSERT_EQ(truth[k].gyro_bias, zero);
  }
}

TEST(SimulateCommand, SameSeedSameBytes) {
  TempDir dir;
  auto run = [&](const std::string& name, const std::string& seed) {
    const auto result = RunTool({"simulate",
                                 "--trajectory",
                                 "random",
                                 "--duration",
                                 "2",
                                 "--seed",
                                 seed,
                                 "--gyro-bias",
                                 "0.01,0,-0.02",
                                 "--out",
                                 dir.File(name),
                                 "--quiet"});
    EXPECT_EQ(result.exit_code, 0) << result.err;
    return ReadFileText(dir.File(name) + "/mav0/imu0/data.csv") +
           ReadFileText(dir.File(name) + "/mav0/state_groundtruth_estimate0/data.csv") +
           ReadFileText(dir.File(name) + "/spline.csv");
  };
  const std::string a = run("a", "42");
  const std::string b = run("b", "42");
  const std::string c = run("c", "43");
  EXPECT_GT(a.size(), 10000u);
  EXPECT_TRUE(a == b) << "same seed, different bytes";
  EXPECT_FALSE(a == c);
}

TEST(SimulateCommand, RecoversASmoothTrajectoryFileWellUnderAMillimetre) {
  TempDir dir;
  // vio_course at 100 Hz in TUM format, on a EuRoC-like time base near 1.4e18 ns.
  const int64_t start_ns = 1'403'715'273'262'142'976;
  const std::vector<StampedPose> poses =
      VioCourseTrajectory().Sample(start_ns, start_ns + 8'000'000'000, 10'000'000);
  std::ostringstream tum;
  WriteTumTrajectory(poses, &tum);
  const std::string file = dir.Write("course.txt", tum.str());
  const std::string out = dir.File("sim");
  const auto result = RunTool({"simulate", "--trajectory-file", file, "--out", out, "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  const YAML::Node yaml = testing::LoadStrictYamlFile(out + "/result.yaml");
  EXPECT_LT(yaml["spline"]["fit_position_rms_m"].as<double>(), kTrajectoryFileTolerance);
  EXPECT_EQ(yaml["start_t_ns"].as<int64_t>(), poses.front().t_ns);  // The file's time base.
  const std::vector<GroundTruthState> truth =
      ReadEurocGroundTruth(out + "/mav0/state_groundtruth_estimate0/data.csv");
  ASSERT_EQ(truth.size(), 1601u);  // 8 s at 200 Hz
  for (size_t k = 0; k < truth.size(); k += 2) {
    // IMU rows every 5 ms, poses every 10 ms: every other row is at a pose time.
    const StampedPose& pose = poses[k / 2];
    ASSERT_EQ(truth[k].t_ns, pose.t_ns);
    ASSERT_LT((truth[k].p_w_s - pose.p).norm(), kTrajectoryFileTolerance) << "row " << k;
  }
}

TEST(SimulateCommand, BadInputExitsTwoWithOneLineAndNoOutput) {
  TempDir dir;
  const std::string out = dir.File("sim");
  const std::string unsorted = dir.Write("unsorted.txt",
                                         "0.0 0 0 0 0 0 0 1\n"
                                         "0.1 0 0 0 0 0 0 1\n"
                                         "0.05 0 0 0 0 0 0 1\n");
  const std::string yaml = dir.Write("imu.yaml",
                                     "gyroscope_noise_density: 1e-4\ngyroscope_random_walk: 1e-5\n"
                                     "accelerometer_noise_density: 1e-3\n"
                                     "accelerometer_random_walk: 1e-3\n");
  const std::vector<testing::BadInvocation> cases = {
      {{"--trajectory", "circle"}, "unknown trajectory"},
      {{"--imu-rate", "0"}, "--imu-rate"},
      {{"--duration", "-1"}, "--duration"},
      {{"--gyro-bias", "1,2"}, "--gyro-bias"},
      {{"--trajectory-file", unsorted}, "unsorted.txt:3"},
      {{"--trajectory-file", dir.File("missing.txt")}, "missing.txt"},
      {{"--imu-yaml", yaml, "--gyroscope_noise_density", "1e-3"}, "either"},
      {{"--gyroscope_noise_density", "-1"}, "gyroscope_noise_density"},
  };
  testing::ExpectEachRefusedWritingNothing({"simulate", "--out", out}, cases, out + "/result.yaml");
}

}  // namespace
}  // namespace splinecal
