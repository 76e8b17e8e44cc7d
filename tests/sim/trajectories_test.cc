#include "splinecal/sim/trajectories.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

// Closed forms against the formula: both sides are a handful of sin/cos, so agreement is to
// rounding (values up to ~25 m).
constexpr double kFormulaTolerance = 1e-12;
// Central differences with step h have truncation error h^2/6 |f'''| (first derivative) and
// h^2/12 |f''''| (second); with h = 1e-3 s and derivatives below ~10 that is ~1e-6, and the
// rounding error eps * |f| / h^2 of the second difference is ~5e-9 (|f| <= 25 m).
constexpr double kDifferenceStep = 1e-3;
constexpr double kDifferenceTolerance = 2e-5;

Eigen::Matrix3d EulerZyx(double roll, double pitch, double yaw) {
  Eigen::Matrix3d rx, ry, rz;
  // clang-format off
  rx << 1, 0, 0,
        0, std::cos(roll), -std::sin(roll),
        0, std::sin(roll), std::cos(roll);
  ry << std::cos(pitch), 0, std::sin(pitch),
        0, 1, 0,
        -std::sin(pitch), 0, std::cos(pitch);
  rz << std::cos(yaw), -std::sin(yaw), 0,
        std::sin(yaw), std::cos(yaw), 0,
        0, 0, 1;
  // clang-format on
  return rz * ry * rx;
}

TEST(VioCourseTrajectory, MatchesTheCourseFormula) {
  const AnalyticTrajectory trajectory = VioCourseTrajectory();
  const double k = kPi / 10.0;
  for (double t : {0.0, 0.37, 5.0, 12.25, 19.99}) {
    const SE3d T_w_s = trajectory.Pose(t);
    const Eigen::Vector3d p(
        15.0 * std::cos(k * t) + 5.0, 20.0 * std::sin(k * t) + 5.0, std::sin(10.0 * k * t) + 5.0);
    EXPECT_LT((T_w_s.translation() - p).norm(), kFormulaTolerance) << "t = " << t;
    const Eigen::Matrix3d R = EulerZyx(0.1 * std::cos(t), 0.2 * std::sin(t), k * t);
    EXPECT_LT((T_w_s.so3().matrix() - R).norm(), kFormulaTolerance) << "t = " << t;
  }
}

void ExpectDerivativesMatchDifferences(const AnalyticTrajectory& trajectory, double t_end) {
  const double h = kDifferenceStep;
  for (double t = 0.1; t < t_end; t += 0.731) {
    const TrajectoryState state = trajectory.Evaluate(t);
    const SE3d before = trajectory.Pose(t - h);
    const SE3d after = trajectory.Pose(t + h);
    const Eigen::Vector3d p = state.T_w_s.translation();
    const Eigen::Vector3d v_numeric = (after.translation() - before.translation()) / (2.0 * h);
    const Eigen::Vector3d a_numeric =
        (after.translation() - 2.0 * p + before.translation()) / (h * h);
    // Body rate: R(t+h) = R(t-h) Exp(2 h w_s) + O(h^3).
    const Eigen::Vector3d w_numeric = (before.so3().inverse() * after.so3()).Log() / (2.0 * h);
    EXPECT_LT((state.v_w - v_numeric).norm(), kDifferenceTolerance)
        << trajectory.name() << " t = " << t;
    EXPECT_LT((state.a_w - a_numeric).norm(), kDifferenceTolerance)
        << trajectory.name() << " t = " << t;
    EXPECT_LT((state.w_s - w_numeric).norm(), kDifferenceTolerance)
        << trajectory.name() << " t = " << t;
  }
}

TEST(AnalyticTrajectory, DerivativesMatchCentralDifferences) {
  ExpectDerivativesMatchDifferences(VioCourseTrajectory(), 20.0);
  ExpectDerivativesMatchDifferences(Figure8Trajectory(), 20.0);
  ExpectDerivativesMatchDifferences(RandomTrajectory(5), 30.0);
}

TEST(AnalyticTrajectory, SampleStampsAndEvaluatesAtTrajectoryTime) {
  const AnalyticTrajectory trajectory = Figure8Trajectory();
  const int64_t start_ns = 1'000'000'000;
  const std::vector<StampedPose> poses =
      trajectory.Sample(start_ns, start_ns + 1'000'000'000, 10'000'000);
  ASSERT_EQ(poses.size(), 101u);
  EXPECT_EQ(poses.front().t_ns, start_ns);
  EXPECT_EQ(poses.back().t_ns, start_ns + 1'000'000'000);
  const SE3d T_w_s = trajectory.Pose(0.5);
  EXPECT_LT((poses[50].p - T_w_s.translation()).norm(), kFormulaTolerance);
  EXPECT_LT(poses[50].q.angularDistance(T_w_s.so3().quaternion()), kFormulaTolerance);
}

TEST(RandomTrajectory, RespectsRateAndAccelerationBounds) {
  RandomTrajectoryOptions options;
  options.max_angular_rate_rad_s = 0.8;
  options.max_acceleration_m_s2 = 3.0;
  for (uint64_t seed : {1u, 2u, 3u, 99u}) {
    const AnalyticTrajectory trajectory = RandomTrajectory(seed, options);
    double max_rate = 0.0;
    double max_accel = 0.0;
    for (double t = 0.0; t < 60.0; t += 0.01) {
      const TrajectoryState state = trajectory.Evaluate(t);
      max_rate = std::max(max_rate, state.w_s.norm());
      max_accel = std::max(max_accel, state.a_w.norm());
    }
    EXPECT_LE(max_rate, options.max_angular_rate_rad_s) << "seed " << seed;
    EXPECT_LE(max_accel, options.max_acceleration_m_s2) << "seed " << seed;
    // And it does move: at least a fifth of each bound is used somewhere.
    EXPECT_GT(max_rate, 0.2 * options.max_angular_rate_rad_s) << "seed " << seed;
    EXPECT_GT(max_accel, 0.2 * options.max_acceleration_m_s2) << "seed " << seed;
  }
}

TEST(RandomTrajectory, SameSeedSameTrajectory) {
  const SE3d a = RandomTrajectory(17).Pose(3.3);
  const SE3d b = RandomTrajectory(17).Pose(3.3);
  const SE3d c = RandomTrajectory(18).Pose(3.3);
  EXPECT_EQ(a.translation(), b.translation());
  EXPECT_EQ(a.so3().quaternion().coeffs(), b.so3().quaternion().coeffs());
  EXPECT_NE(a.translation(), c.translation());
}

TEST(RandomTrajectory, RejectsBadOptions) {
  RandomTrajectoryOptions options;
  options.max_acceleration_m_s2 = 0.0;
  EXPECT_THROW(RandomTrajectory(1, options), Error);
  options = RandomTrajectoryOptions();
  options.min_period_s = 5.0;
  options.max_period_s = 1.0;
  EXPECT_THROW(RandomTrajectory(1, options), Error);
}

TEST(MakeTrajectory, KnowsTheThreeNamesAndRejectsOthers) {
  EXPECT_EQ(MakeTrajectory("vio_course", 0).name(), "vio_course");
  EXPECT_EQ(MakeTrajectory("figure8", 0).name(), "figure8");
  EXPECT_EQ(MakeTrajectory("random", 4).name(), "random");
  try {
    MakeTrajectory("circle", 0);
    FAIL() << "expected splinecal::Error";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("vio_course"), std::string::npos);
  }
}

}  // namespace
}  // namespace splinecal
