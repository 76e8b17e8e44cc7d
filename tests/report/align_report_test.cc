#include "splinecal/report/align_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <cmath>
#include <string>
#include <vector>

#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::StartsWith;

AlignResult SmallResult() {
  AlignResult r;
  r.success = true;
  r.message = "aligned";
  r.scale = 2.5;
  r.gravity_c0 = Eigen::Vector3d(0.0, -9.81, 0.0);
  // A rotation by 4 rad: its quaternion has w = cos(2) < 0 unless flipped.
  r.R_w_c0 = SO3d::Exp(Eigen::Vector3d(0.0, 0.0, 4.0));
  r.states_w.resize(3);
  r.num_ignored_frames = 1;
  return r;
}

TEST(AlignResultYaml, KeysQuaternionsWithNonNegativeWAndTheOptions) {
  AlignOptions options;
  options.gravity_m_s2 = 9.81;
  const std::string text = AlignResultYaml(SmallResult(), options);
  EXPECT_THAT(text, StartsWith("# splinecal align: "));
  const YAML::Node yaml = testing::LoadStrictYaml(text);
  EXPECT_TRUE(yaml["success"].as<bool>());
  EXPECT_DOUBLE_EQ(yaml["scale"].as<double>(), 2.5);
  EXPECT_EQ(yaml["num_frames"].as<int>(), 3);
  EXPECT_EQ(yaml["num_ignored_frames"].as<int>(), 1);
  EXPECT_DOUBLE_EQ(yaml["gravity_m_s2"].as<double>(), 9.81);
  const std::vector<double> q = yaml["R_w_c0"].as<std::vector<double>>();
  ASSERT_EQ(q.size(), 4u);
  EXPECT_GE(q[0], 0.0);
  EXPECT_NEAR(std::abs(q[0]), std::abs(std::cos(2.0)), 1e-12);
  EXPECT_NEAR(std::abs(q[3]), std::abs(std::sin(2.0)), 1e-12);
  EXPECT_FALSE(yaml["R_cam_imu"]);  // not estimated
}

TEST(AlignResultYaml, EstimatedRotationExtrinsicIsWritten) {
  AlignResult r = SmallResult();
  r.rotation_extrinsic_estimated = true;
  const YAML::Node yaml = testing::LoadStrictYaml(AlignResultYaml(r, AlignOptions()));
  EXPECT_EQ(yaml["R_cam_imu"].size(), 4u);
}

}  // namespace
}  // namespace splinecal
