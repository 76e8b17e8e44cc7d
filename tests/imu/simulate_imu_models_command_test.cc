// `splinecal simulate --imu-intrinsics`: Kalibr's IMU models and several IMUs, end to end.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/spline_csv.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::RefusedInOneLine;
using testing::RunTool;
using testing::TempDir;

// The readings pass through 17-digit text (EuRoC csv, spline.csv, imu_models.yaml): the model
// applied again to the read-back spline agrees to ~1e-13 relative of O(10) m/s^2.
constexpr double kTextRoundTrip = 1e-9;

const char kTwoImus[] =
    "imu0:\n"
    "  model: scale-misalignment\n"
    "  accelerometers:\n"
    "    M: [[1.01, 0, 0], [0.008, 0.99, 0], [-0.006, 0.004, 1.005]]\n"
    "  gyroscopes:\n"
    "    M: [[0.99, 0, 0], [-0.005, 1.012, 0], [0.007, -0.003, 1.008]]\n"
    "    A: [[0.001, 0, 0], [0, -0.0008, 0], [0, 0, 0.0009]]\n"
    "    C_gyro_i: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n"
    "imu1:\n"
    "  model: scale-misalignment-size-effect\n"
    "  T_i_b: [[0, -1, 0, 0.05], [1, 0, 0, -0.1], [0, 0, 1, 0.02], [0, 0, 0, 1]]\n"
    "  time_offset: 0.002\n"
    "  accelerometers:\n"
    "    M: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n"
    "    rx_i: [0, 0, 0]\n"
    "    ry_i: [0.005, 0, -0.003]\n"
    "    rz_i: [-0.004, 0.006, 0]\n"
    "  gyroscopes:\n"
    "    M: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n"
    "    A: [[0, 0, 0], [0, 0, 0], [0, 0, 0]]\n"
    "    C_gyro_i: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n";

TEST(SimulateCommand, WritesEveryImuOfTheIntrinsicsFileThroughItsModel) {
  TempDir dir;
  const std::string out = dir.File("sim");
  const std::string intrinsics = dir.Write("imus.yaml", kTwoImus);
  const auto result = RunTool({"simulate",
                               "--duration",
                               "1",
                               "--noise-free",
                               "--imu-intrinsics",
                               intrinsics,
                               "--out",
                               out,
                               "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("simulated 2 IMU(s), imu0 model scale-misalignment"));
  const std::vector<ImuCalibration> truth = ReadImuModelsYaml(out + "/imu_models.yaml");
  ASSERT_EQ(truth.size(), 2u);
  EXPECT_EQ(truth[1].model, ImuModelKind::kScaleMisalignmentSizeEffect);
  const SE3Splined spline = ReadSplineCsv(out + "/spline.csv");
  for (int k = 0; k < 2; ++k) {
    const std::vector<ImuSample> imu =
        ReadEurocImu(out + "/mav0/imu" + std::to_string(k) + "/data.csv");
    ASSERT_EQ(imu.size(), 201u);
    const int64_t offset_ns = k == 0 ? 0 : 2'000'000;
    for (size_t n = 0; n < imu.size(); n += 20) {
      const BodyMotion<double> motion =
          SplineBodyMotion(spline, spline.SegmentAtNs(imu[n].t_ns + offset_ns), GravityWorld());
      Eigen::Vector3d gyro, accel;
      const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
      PredictImuReadings(
          truth[k].model, truth[k].intrinsics, motion, zero, zero, &gyro, &accel, nullptr, nullptr);
      EXPECT_LT((imu[n].gyro - gyro).norm(), kTextRoundTrip) << k << " " << n;
      EXPECT_LT((imu[n].accel - accel).norm(), kTextRoundTrip) << k << " " << n;
    }
  }
  const YAML::Node yaml = testing::LoadStrictYamlFile(out + "/result.yaml");
  EXPECT_EQ(yaml["imu_model"].as<std::string>(), "scale-misalignment");
  EXPECT_EQ(yaml["num_imus"].as<int>(), 2);
}

TEST(SimulateCommand, BadIntrinsicsFileExitsTwoWithOneLineAndNoOutput) {
  TempDir dir;
  const std::string out = dir.File("sim");
  std::string text = kTwoImus;
  text.replace(text.find("[[1.01, 0, 0]"), 13, "[[1.01, 0.2, 0]");
  const std::string bad = dir.Write("bad.yaml", text);
  const auto result = RunTool({"simulate", "--imu-intrinsics", bad, "--out", out});
  EXPECT_TRUE(
      RefusedInOneLine(result, "bad.yaml:4: imu0/accelerometers/M: must be lower triangular"));
  EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml"));
}

}  // namespace
}  // namespace splinecal
