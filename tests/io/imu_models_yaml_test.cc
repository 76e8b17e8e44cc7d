#include "splinecal/io/imu_models_yaml.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <functional>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/lie/so3.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

// Rotations pass through a quaternion on reading (ReadRotation): rounding only.
constexpr double kRotationRoundTrip = 1e-15;

std::string MessageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

std::vector<ImuCalibration> ThreeImus() {
  ImuCalibration imu0;
  imu0.model = ImuModelKind::kScaleMisalignment;
  imu0.intrinsics.M_a << 1.01, 0, 0, 0.008, 0.99, 0, -0.006, 0.004, 1.005;
  imu0.intrinsics.M_g << 0.99, 0, 0, -0.005, 1.012, 0, 0.007, -0.003, 1.008;
  imu0.intrinsics.A << 1e-3, -2e-4, 5e-4, 3e-4, -8e-4, 1e-4, -6e-4, 2e-4, 9e-4;
  imu0.intrinsics.C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.01, -0.015, 0.005)).matrix();
  ImuCalibration imu1;
  imu1.intrinsics.C_i_b = SO3d::Exp(Eigen::Vector3d(0.3, -1.2, 2.0)).matrix();
  imu1.intrinsics.r_b = Eigen::Vector3d(0.1, -0.05, 0.02);
  imu1.time_offset_s = 0.003;
  ImuCalibration imu2 = imu0;
  imu2.model = ImuModelKind::kScaleMisalignmentSizeEffect;
  imu2.intrinsics.C_i_b = imu1.intrinsics.C_i_b;
  imu2.intrinsics.r_b = Eigen::Vector3d(-0.2, 0.0, 0.07);
  imu2.intrinsics.ry_i = Eigen::Vector3d(0.005, 0.0, -0.003);
  imu2.intrinsics.rz_i = Eigen::Vector3d(-0.004, 0.006, 0.0);
  return {imu0, imu1, imu2};
}

TEST(ImuModelsYaml, RoundTripsEveryModel) {
  TempDir dir;
  const std::vector<ImuCalibration> imus = ThreeImus();
  const std::string text = ImuModelsYamlText(imus);
  EXPECT_THAT(text, HasSubstr("imu0:\n  model: \"scale-misalignment\"\n"));
  EXPECT_THAT(text, HasSubstr("model: \"scale-misalignment-size-effect\""));
  EXPECT_THAT(text, HasSubstr("C_gyro_i:"));
  EXPECT_THAT(text, HasSubstr("rx_i: [0, 0, 0]"));
  const std::vector<ImuCalibration> back = ReadImuModelsYaml(dir.Write("imu.yaml", text));
  ASSERT_EQ(back.size(), 3u);
  for (size_t k = 0; k < 3; ++k) {
    const ImuIntrinsicsd& a = imus[k].intrinsics;
    const ImuIntrinsicsd& b = back[k].intrinsics;
    EXPECT_EQ(back[k].model, imus[k].model);
    EXPECT_EQ(back[k].time_offset_s, imus[k].time_offset_s);
    EXPECT_TRUE(b.C_i_b.isApprox(a.C_i_b, kRotationRoundTrip)) << k;
    EXPECT_TRUE(b.r_b.isApprox(a.r_b, 1e-15) || a.r_b.isZero()) << k;
    EXPECT_LT((b.r_b - a.r_b).norm(), 1e-15) << k;
    EXPECT_EQ(b.M_a, a.M_a);
    EXPECT_EQ(b.M_g, a.M_g);
    EXPECT_EQ(b.A, a.A);
    EXPECT_LT((b.C_gyro_i - a.C_gyro_i).cwiseAbs().maxCoeff(), kRotationRoundTrip);
    EXPECT_EQ(b.ry_i, a.ry_i);
    EXPECT_EQ(b.rz_i, a.rz_i);
  }
}

TEST(ImuModelsYaml, ReadsKalibrsCalibratedSectionWithItsNoiseKeys) {
  TempDir dir;
  const std::vector<ImuCalibration> imus = ReadImuModelsYaml(
      dir.Write("imu.yaml",
                "imu0:\n"
                "  T_i_b:\n  - [1.0, 0.0, 0.0, 0.0]\n  - [0.0, 1.0, 0.0, 0.0]\n"
                "  - [0.0, 0.0, 1.0, 0.0]\n  - [0.0, 0.0, 0.0, 1.0]\n"
                "  accelerometer_noise_density: 0.006\n  accelerometer_random_walk: 0.0002\n"
                "  gyroscope_noise_density: 0.0004\n  gyroscope_random_walk: 4.0e-06\n"
                "  model: calibrated\n  rostopic: /imu0\n  time_offset: 0.0\n"
                "  update_rate: 200.0\n"));
  ASSERT_EQ(imus.size(), 1u);
  EXPECT_EQ(imus[0].model, ImuModelKind::kCalibrated);
  EXPECT_EQ(imus[0].intrinsics.C_i_b, Eigen::Matrix3d::Identity());
}

TEST(ImuModelsYaml, BadFilesNameTheFileLineAndProblem) {
  TempDir dir;
  const std::string good = ImuModelsYamlText(ThreeImus());
  const auto replaced = [&](const std::string& from, const std::string& to) {
    std::string text = good;
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    return text.replace(at, from.size(), to);
  };
  struct Case {
    std::string text;
    std::string message;
  };
  const std::vector<Case> cases = {
      {"imu1:\n  model: calibrated\n", "no imu0 section"},
      {replaced("model: \"scale-misalignment\"\n", "model: scaled\n"),
       ":2: imu0/model: unknown IMU model 'scaled'"},
      {replaced("    M:\n      - [1.01, 0, 0]", "    M:\n      - [1.01, 0.1, 0]"),
       "must be lower triangular"},
      {replaced("    M:\n      - [1.01, 0, 0]", "    M:\n      - [3, 0, 0]"),
       "plausible scale factor"},
      {replaced("rx_i: [0, 0, 0]", "rx_i: [0.001, 0, 0]"), "rx_i: must be 0"},
      {replaced("ry_i: [0.0050000000000000001, 0", "ry_i: [5, 0"), "ry_i"},
      {replaced("T_i_b:\n    - [1, 0, 0, 0]", "T_i_b:\n    - [1, 0, 0, 0.5]"),
       "imu0/T_i_b: the first IMU is the reference"},
      {replaced("T_i_b:\n    - [1, 0, 0, 0]", "T_i_b:\n    - [2, 0, 0, 0]"),
       "not a rigid transform"},
      {good + "imu4:\n  model: calibrated\n", "unexpected top-level key 'imu4'"},
  };
  for (const Case& c : cases) {
    const std::string path = dir.Write("bad.yaml", c.text);
    const std::string message = MessageOf([&] { ReadImuModelsYaml(path); });
    EXPECT_THAT(message, HasSubstr("bad.yaml")) << c.message;
    EXPECT_THAT(message, HasSubstr(c.message)) << message;
  }
}

}  // namespace
}  // namespace splinecal
