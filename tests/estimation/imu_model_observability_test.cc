#include "splinecal/estimation/imu_model_observability.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <set>
#include <string>
#include <vector>

#include "splinecal/imu/imu_model.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

constexpr int64_t kDtNs = 100'000'000;  // 0.1 s knots
constexpr int kNumPoses = 64;           // 6.1 s of valid range
// Per-sample noise of the ADIS16448 at 200 Hz (EuRoC's imu.yaml: 1.6968e-4 rad/s/sqrt(Hz) and
// 2.0e-3 m/s^2/sqrt(Hz) times sqrt(200 Hz)): the weights of a real recording.
constexpr double kSigmaGyro = 2.4e-3;
constexpr double kSigmaAccel = 2.8e-2;

// Control poses of a motion that translates along every axis (0.3 m sinusoids of periods
// 1.3-2.1 s) and rotates: about z alone (constant_axis), or about all three axes.
std::vector<SE3d> Motion(bool constant_axis) {
  std::vector<SE3d> poses;
  for (int i = 0; i < kNumPoses; ++i) {
    const double t = 0.1 * i;
    const Eigen::Vector3d p(0.3 * std::sin(2 * kPi * t / 1.3), 0.3 * std::sin(2 * kPi * t / 1.7),
                            0.3 * std::sin(2 * kPi * t / 2.1));
    Eigen::Vector3d phi(0.0, 0.0, 1.2 * t);
    if (!constant_axis) {
      phi.x() = 0.5 * std::sin(2 * kPi * t / 1.9);
      phi.y() = 0.5 * std::sin(2 * kPi * t / 2.3);
    }
    poses.emplace_back(SO3d::Exp(phi), p);
  }
  return poses;
}

std::set<std::string> UndeterminedNames(bool constant_axis,
                                        std::vector<ImuModelParameter>* out,
                                        bool hold = false) {
  KnotLayout layout;
  layout.dt_ns = kDtNs;
  layout.num_control_poses = kNumPoses;
  const std::vector<SE3d> poses = Motion(constant_axis);
  const SE3Splined spline(poses, 0, kDtNs);
  std::vector<ImuSample> imu;
  for (int64_t t = layout.start_time_ns(); t <= layout.end_time_ns(); t += 5'000'000) {
    ImuSample s;
    s.t_ns = t;
    PredictImu<double>(spline, spline.SegmentAtNs(t), GravityWorld(), Eigen::Vector3d::Zero(),
                       Eigen::Vector3d::Zero(), &s.gyro, &s.accel);
    imu.push_back(s);
  }
  SplineProblem problem(layout, poses, BiasSpline());
  problem.SetImuModel(ImuModelKind::kScaleMisalignment);
  problem.Reset();
  problem.AddImuResiduals(imu, kSigmaGyro, kSigmaAccel);
  *out = UndeterminedImuModelParameters(&problem);
  if (hold) {
    // Held entries go back to nominal and leave the blocks' tangents (SubsetManifold).
    problem.imu_model()->m_g[0] = 1.1;
    for (const ImuModelParameter& p : *out) problem.HoldImuModelEntry(p.block, p.index);
    problem.Reset();
    EXPECT_EQ(problem.imu_model()->m_g[0], 1.0);
    EXPECT_EQ(problem.problem().ParameterBlockTangentSize(problem.imu_model()->m_g.data()), 1);
    EXPECT_EQ(problem.problem().ParameterBlockTangentSize(problem.imu_model()->phi_gyro_i.data()),
              2);
    EXPECT_EQ(problem.problem().ParameterBlockTangentSize(problem.imu_model()->m_a.data()), 6);
    EXPECT_EQ(problem.HeldImuModelEntries(problem.imu_model()->m_g.data()),
              std::vector<int>({0, 1, 2, 3, 4}));
  }
  std::set<std::string> names;
  for (const ImuModelParameter& p : *out) names.insert(p.name);
  return names;
}

// Rotation about z alone: the gyro's x and y readings carry only noise, so M_g's first two
// columns and the gyro frame's rotation about z (which mixes x and y readings only) are not
// determined; everything read through z rotation or the specific force is.
TEST(ImuModelObservability, ConstantAxisRotationNamesTheUnexcitedGyroParameters) {
  std::vector<ImuModelParameter> undetermined;
  const std::set<std::string> names = UndeterminedNames(true, &undetermined, /*hold=*/true);
  const std::set<std::string> expected = {"M_g(0,0)", "M_g(1,0)", "M_g(1,1)",
                                          "M_g(2,0)", "M_g(2,1)", "C_gyro_i(z)"};
  EXPECT_EQ(names, expected);
  const std::string warning = UndeterminedImuModelWarning(undetermined);
  std::printf("%s\n", warning.c_str());
  EXPECT_THAT(warning, HasSubstr("M_g(0,0), M_g(1,0), M_g(2,0) (needs rotation about the gyro's "
                                 "x axis)"));
  EXPECT_THAT(warning, HasSubstr("M_g(1,1), M_g(2,1) (needs rotation about the gyro's y axis)"));
  EXPECT_THAT(warning, HasSubstr("C_gyro_i(z) (needs rotation about an axis other than z)"));
}

TEST(ImuModelObservability, ThreeAxisRotationDeterminesEveryParameter) {
  std::vector<ImuModelParameter> undetermined;
  EXPECT_TRUE(UndeterminedNames(false, &undetermined).empty());
}

}  // namespace
}  // namespace splinecal
