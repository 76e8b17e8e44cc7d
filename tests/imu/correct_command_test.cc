// `splinecal correct` end to end: the tool's corrected file is the library's correction, and bad
// input exits 2 with one line and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "splinecal/imu/correct_imu.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::RunTool;
using testing::TempDir;

// The tool reads the 17-digit text the library result is compared with: rounding of the
// text round trip only.
constexpr double kTextRoundTrip = 1e-12;

const char kImus[] =
    "imu0:\n"
    "  model: scale-misalignment-size-effect\n"
    "  accelerometers:\n"
    "    M: [[1.01, 0, 0], [0.008, 0.99, 0], [-0.006, 0.004, 1.005]]\n"
    "    ry_i: [0.005, 0, -0.003]\n"
    "    rz_i: [-0.004, 0.006, 0]\n"
    "  gyroscopes:\n"
    "    M: [[0.99, 0, 0], [-0.005, 1.012, 0], [0.007, -0.003, 1.008]]\n"
    "    A: [[0.001, 0, 0], [0, -0.0008, 0], [0, 0, 0.0009]]\n"
    "    C_gyro_i: [[1, 0, 0], [0, 1, 0], [0, 0, 1]]\n";

TEST(CorrectCommand, WritesTheLibrarysCorrection) {
  TempDir dir;
  const std::string intrinsics = dir.Write("imus.yaml", kImus);
  const std::string sim = dir.File("sim");
  ASSERT_EQ(RunTool({"simulate",
                     "--duration",
                     "1",
                     "--trajectory",
                     "figure8",
                     "--imu-intrinsics",
                     intrinsics,
                     "--out",
                     sim,
                     "--quiet"})
                .exit_code,
            0);
  const std::string raw_path = sim + "/mav0/imu0/data.csv";
  const std::string out = dir.File("corrected");
  const auto result = RunTool({"correct",
                               "--imu",
                               raw_path,
                               "--imu-intrinsics",
                               intrinsics,
                               "--gyro-bias",
                               "0.01,0,0",
                               "--out",
                               out,
                               "--quiet"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out,
              HasSubstr("corrected 201 readings with the "
                        "scale-misalignment-size-effect model of imu0"));
  ImuCorrectionOptions options;
  options.gyro_bias = Eigen::Vector3d(0.01, 0, 0);
  const std::vector<ImuSample> expected =
      CorrectImuReadings(ReadImuModelsYaml(intrinsics)[0], ReadEurocImu(raw_path), options);
  const std::vector<ImuSample> written = ReadEurocImu(out + "/mav0/imu0/data.csv");
  ASSERT_EQ(written.size(), expected.size());
  for (size_t k = 0; k < written.size(); ++k) {
    EXPECT_EQ(written[k].t_ns, expected[k].t_ns);
    EXPECT_LT((written[k].gyro - expected[k].gyro).norm(), kTextRoundTrip) << k;
    EXPECT_LT((written[k].accel - expected[k].accel).norm(), kTextRoundTrip) << k;
  }
  const YAML::Node yaml = testing::LoadStrictYamlFile(out + "/result.yaml");
  EXPECT_EQ(yaml["model"].as<std::string>(), "scale-misalignment-size-effect");
  EXPECT_EQ(yaml["num_samples"].as<int>(), 201);
  EXPECT_EQ(yaml["derivative_half_window"].as<int>(), 2);
}

TEST(CorrectCommand, BadInputExitsTwoWithOneLineAndNoOutput) {
  TempDir dir;
  const std::string intrinsics = dir.Write("imus.yaml", kImus);
  const std::string imu = dir.Write("imu.csv",
                                    "#timestamp [ns],wx,wy,wz,ax,ay,az\n"
                                    "1000,0,0,0,0,0,9.81\n"
                                    "2000,0,0,0,0,0,9.81\n");
  std::string bad_model = kImus;
  bad_model.replace(bad_model.find("size-effect"), 11, "sizeeffect");
  const std::string bad = dir.Write("bad.yaml", bad_model);
  const std::string out = dir.File("out");
  const std::vector<testing::BadInvocation> cases = {
      {{"--imu", imu}, "--imu-intrinsics"},
      {{"--imu-intrinsics", intrinsics}, "--imu"},
      {{"--imu", imu, "--imu-intrinsics", intrinsics, "--imu-index", "1"},
       "imus.yaml: --imu-index 1: the file has 1 IMU(s)"},
      {{"--imu", imu, "--imu-intrinsics", bad}, "bad.yaml:2: imu0/model: unknown IMU model"},
      {{"--imu", imu, "--imu-intrinsics", intrinsics, "--derivative-window", "0"},
       "--derivative-window"},
      {{"--imu", dir.File("missing.csv"), "--imu-intrinsics", intrinsics}, "missing.csv"},
  };
  testing::ExpectEachRefusedWritingNothing({"correct", "--out", out}, cases, out + "/result.yaml");
}

}  // namespace
}  // namespace splinecal
