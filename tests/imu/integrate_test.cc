#include "splinecal/imu/integrate.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/euroc.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/units.h"
#include "testing/paths.h"
#include "testing/shared_data.h"
#include "testing/static_phase.h"

namespace splinecal {
namespace {

constexpr double kGravity = 9.81;
// Motions every method integrates exactly (constant rate, constant world acceleration): only
// rounding remains, ~1e-15 relative per step over a few thousand steps.
constexpr double kExactTolerance = 1e-9;

const Eigen::Vector3d kGravityW(0.0, 0.0, -kGravity);

// Noise-free IMU readings of an analytic trajectory at rate_hz for duration_s, t_ns = k * period
// (trajectory time t_ns * 1e-9), and the true states at the same times. The readings are the
// closed forms, so this tests the integrator alone (no spline).
struct AnalyticData {
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
};

AnalyticData MakeAnalyticData(const AnalyticTrajectory& trajectory,
                              double rate_hz,
                              double duration_s) {
  AnalyticData data;
  const int64_t period_ns = static_cast<int64_t>(std::llround(1e9 / rate_hz));
  const int64_t end_ns = static_cast<int64_t>(std::llround(duration_s * 1e9));
  for (int64_t t_ns = 0; t_ns <= end_ns; t_ns += period_ns) {
    const TrajectoryState state = trajectory.Evaluate(static_cast<double>(t_ns) * 1e-9);
    ImuSample sample;
    sample.t_ns = t_ns;
    sample.gyro = state.w_s;
    // docs/conventions.md "IMU model": accel = R_w_s^T (a_w - g_w).
    sample.accel = state.T_w_s.so3().inverse() * (state.a_w - kGravityW);
    data.imu.push_back(sample);
    GroundTruthState truth;
    truth.t_ns = t_ns;
    truth.p_w_s = state.T_w_s.translation();
    truth.q_w_s = state.T_w_s.so3().quaternion();
    truth.v_w = state.v_w;
    data.truth.push_back(truth);
  }
  return data;
}

NavState IntegrateAll(const AnalyticData& data, IntegrationMethod method) {
  const NavState start = NavStateFromGroundTruth(data.truth.front());
  return IntegrateImu(data.imu, start, data.imu.back().t_ns, ImuBias(), kGravityW, method);
}

double FinalPositionError(const AnalyticData& data, IntegrationMethod method) {
  return (IntegrateAll(data, method).p_w_s - data.truth.back().p_w_s).norm();
}

double FinalRotationError(const AnalyticData& data, IntegrationMethod method) {
  const SO3d R_true = SO3d::FromQuaternion(data.truth.back().q_w_s);
  return (R_true.inverse() * IntegrateAll(data, method).R_w_s).Log().norm();
}

constexpr IntegrationMethod kAllMethods[] = {
    IntegrationMethod::kEuler, IntegrationMethod::kMidpoint, IntegrationMethod::kRk4};

// The step helpers against lie/so3.h on both sides of their series threshold (0.1 rad) and at
// tiny angles: agreement to a few ulp of the unit-size results.
constexpr double kStepHelperTolerance = 4e-16;

TEST(IntegrateInternal, StepHelpersMatchTheLieGroupFunctions) {
  const Eigen::Vector3d axis = Eigen::Vector3d(0.3, -0.5, 0.8).normalized();
  const Eigen::Vector3d x(0.7, -0.2, 0.4);
  for (double angle : {0.0, 1e-9, 1e-4, 0.01, 0.05, 0.0999, 0.1001, 0.5, 3.0}) {
    const Eigen::Vector3d phi = angle * axis;
    const SO3d expected = SO3d::Exp(phi);
    EXPECT_LT(internal::StepExp(phi).quaternion().angularDistance(expected.quaternion()),
              kStepHelperTolerance * 4)
        << "angle " << angle;
    EXPECT_NEAR(internal::StepExp(phi).quaternion().squaredNorm(), 1.0, kStepHelperTolerance)
        << "angle " << angle;
    EXPECT_LT((internal::RotateByExp(phi, x) - expected * x).norm(), kStepHelperTolerance)
        << "angle " << angle;
    const Eigen::Vector3d jr_inv_x = RightJacobianInverseSO3(phi) * x;
    EXPECT_LT((internal::RightJacobianInverseTimes(phi, x) - jr_inv_x).norm(),
              kStepHelperTolerance * 4)
        << "angle " << angle;
  }
}

TEST(IntegrationMethod, NamesRoundTripAndListsParse) {
  for (IntegrationMethod method : kAllMethods) {
    EXPECT_EQ(ParseIntegrationMethod(IntegrationMethodName(method)), method);
  }
  const std::vector<IntegrationMethod> methods = ParseIntegrationMethods("euler, rk4,euler");
  ASSERT_EQ(methods.size(), 2u);
  EXPECT_EQ(methods[0], IntegrationMethod::kEuler);
  EXPECT_EQ(methods[1], IntegrationMethod::kRk4);
  EXPECT_THROW(ParseIntegrationMethod("heun"), Error);
  EXPECT_THROW(ParseIntegrationMethods(""), Error);
}

// Readings sampled every 5 ms for 10 s from a motion with constant body rate w_s, constant world
// acceleration a_w and the given start pose and velocity.
std::vector<ImuSample> ConstantRateImu(const SO3d& R0,
                                       const Eigen::Vector3d& w_s,
                                       const Eigen::Vector3d& a_w) {
  std::vector<ImuSample> imu;
  for (int64_t k = 0; k <= 2000; ++k) {
    ImuSample sample;
    sample.t_ns = 1'000'000'000 + k * 5'000'000;
    const SO3d R = R0 * SO3d::Exp(w_s * (k * 0.005));
    sample.gyro = w_s;
    sample.accel = R.inverse() * (a_w - kGravityW);
    imu.push_back(sample);
  }
  return imu;
}

void ExpectExactConstantRateMotion(const SO3d& R0,
                                   const Eigen::Vector3d& w_s,
                                   const Eigen::Vector3d& a_w,
                                   const std::vector<IntegrationMethod>& methods) {
  const Eigen::Vector3d v0(1.0, 2.0, -0.5);
  const Eigen::Vector3d p0(3.0, 1.0, 2.0);
  const std::vector<ImuSample> imu = ConstantRateImu(R0, w_s, a_w);
  NavState start;
  start.t_ns = imu.front().t_ns;
  start.p_w_s = p0;
  start.R_w_s = R0;
  start.v_w = v0;
  const double t_end = 10.0;
  for (IntegrationMethod method : methods) {
    const NavState end = IntegrateImu(imu, start, imu.back().t_ns, ImuBias(), kGravityW, method);
    EXPECT_LT((end.p_w_s - (p0 + v0 * t_end + 0.5 * a_w * t_end * t_end)).norm(), kExactTolerance)
        << IntegrationMethodName(method);
    EXPECT_LT((end.v_w - (v0 + a_w * t_end)).norm(), kExactTolerance)
        << IntegrationMethodName(method);
    EXPECT_LT((end.R_w_s.inverse() * R0 * SO3d::Exp(w_s * t_end)).Log().norm(), kExactTolerance)
        << IntegrationMethodName(method);
  }
}

TEST(IntegrateImu, ConstantRateAndConstantAccelerationAreExactForEulerAndMidpoint) {
  // Spinning at a constant body rate while accelerating at a constant a_w: Euler and midpoint
  // use the readings only at the samples, where R_k a_k = a_w - g_w exactly, and Exp of a
  // constant rate is exact, so both reproduce the motion to rounding. (RK4 also evaluates at
  // h/2, where the linearly interpolated body acceleration differs from the rotating one by
  // ~(h |w|)^2 / 8 |a|: not exact here, see the next test.)
  ExpectExactConstantRateMotion(SO3d::Exp(Eigen::Vector3d(0.1, 0.2, -0.3)),
                                Eigen::Vector3d(0.3, -0.2, 0.5),
                                Eigen::Vector3d(0.4, -0.1, 0.2),
                                {IntegrationMethod::kEuler, IntegrationMethod::kMidpoint});
}

TEST(IntegrateImu, ConstantReadingsAreExactForEveryMethod) {
  // Spinning about the specific-force axis keeps both readings constant (so their linear
  // interpolation is exact too): every method reproduces the motion to rounding.
  const SO3d R0 = SO3d::Exp(Eigen::Vector3d(0.1, 0.2, -0.3));
  const Eigen::Vector3d a_w(0.4, -0.1, 0.2);
  const Eigen::Vector3d w_s = 0.7 * (R0.inverse() * (a_w - kGravityW)).normalized();
  ExpectExactConstantRateMotion(
      R0,
      w_s,
      a_w,
      {IntegrationMethod::kEuler, IntegrationMethod::kMidpoint, IntegrationMethod::kRk4});
}

TEST(IntegrateImu, OrientationStaysUnitOverManySteps) {
  // 100000 steps of a fast tumble: without renormalisation |q| would drift by ~1e-11.
  std::vector<ImuSample> imu(100001);
  for (size_t k = 0; k < imu.size(); ++k) {
    imu[k].t_ns = static_cast<int64_t>(k) * 5'000'000;
    imu[k].gyro = Eigen::Vector3d(3.0 * std::sin(0.01 * k), 2.0, -1.0 + std::cos(0.003 * k));
    imu[k].accel = Eigen::Vector3d(0.0, 0.0, kGravity);
  }
  for (IntegrationMethod method : kAllMethods) {
    const NavState end =
        IntegrateImu(imu, NavState(), imu.back().t_ns, ImuBias(), kGravityW, method);
    EXPECT_NEAR(end.R_w_s.quaternion().norm(), 1.0, 1e-14) << IntegrationMethodName(method);
  }
}

TEST(IntegrateImu, BiasesAreSubtracted) {
  // A level IMU at rest with biased readings stays put once the biases are given.
  ImuBias bias;
  bias.gyro = Eigen::Vector3d(0.01, -0.02, 0.005);
  bias.accel = Eigen::Vector3d(0.1, 0.05, -0.2);
  std::vector<ImuSample> imu(401);
  for (size_t k = 0; k < imu.size(); ++k) {
    imu[k].t_ns = static_cast<int64_t>(k) * 5'000'000;
    imu[k].gyro = bias.gyro;
    imu[k].accel = Eigen::Vector3d(0.0, 0.0, kGravity) + bias.accel;
  }
  for (IntegrationMethod method : kAllMethods) {
    const NavState end = IntegrateImu(imu, NavState(), imu.back().t_ns, bias, kGravityW, method);
    EXPECT_LT(end.p_w_s.norm(), kExactTolerance) << IntegrationMethodName(method);
    EXPECT_LT(end.v_w.norm(), kExactTolerance) << IntegrationMethodName(method);
    EXPECT_LT(end.R_w_s.Log().norm(), kExactTolerance) << IntegrationMethodName(method);
  }
}

TEST(IntegrateImu, StartAndEndBetweenSamplesRecordEveryState) {
  const AnalyticData data = MakeAnalyticData(VioCourseTrajectory(), 200.0, 2.0);
  // Start 1.2 ms after sample 10, end 3.1 ms after sample 300: the first and last steps are
  // partial, with interpolated readings.
  const int64_t start_ns = data.imu[10].t_ns + 1'200'000;
  const int64_t end_ns = data.imu[300].t_ns + 3'100'000;
  const TrajectoryState truth_start = VioCourseTrajectory().Evaluate(start_ns * 1e-9);
  const TrajectoryState truth_end = VioCourseTrajectory().Evaluate(end_ns * 1e-9);
  NavState start;
  start.t_ns = start_ns;
  start.p_w_s = truth_start.T_w_s.translation();
  start.R_w_s = truth_start.T_w_s.so3();
  start.v_w = truth_start.v_w;
  std::vector<NavState> trajectory;
  const NavState end = IntegrateImu(
      data.imu, start, end_ns, ImuBias(), kGravityW, IntegrationMethod::kRk4, &trajectory);
  ASSERT_EQ(trajectory.size(), 292u);  // start, samples 11..300, end.
  EXPECT_EQ(trajectory.front().t_ns, start_ns);
  EXPECT_EQ(trajectory[1].t_ns, data.imu[11].t_ns);
  EXPECT_EQ(trajectory[290].t_ns, data.imu[300].t_ns);
  EXPECT_EQ(trajectory.back().t_ns, end_ns);
  EXPECT_EQ(trajectory.back().p_w_s, end.p_w_s);
  // 1.45 s of RK4 at 200 Hz on noise-free data: well under a millimetre.
  EXPECT_LT((end.p_w_s - truth_end.T_w_s.translation()).norm(), 1e-3);
}

TEST(IntegrateImu, RejectsTimesOutsideTheData) {
  const AnalyticData data = MakeAnalyticData(VioCourseTrajectory(), 200.0, 1.0);
  NavState start = NavStateFromGroundTruth(data.truth.front());
  start.t_ns = data.imu.front().t_ns - 1;
  EXPECT_THROW(
      IntegrateImu(
          data.imu, start, data.imu.back().t_ns, ImuBias(), kGravityW, IntegrationMethod::kEuler),
      Error);
  start.t_ns = data.imu.front().t_ns;
  EXPECT_THROW(IntegrateImu(data.imu,
                            start,
                            data.imu.back().t_ns + 1,
                            ImuBias(),
                            kGravityW,
                            IntegrationMethod::kEuler),
               Error);
  EXPECT_THROW(
      IntegrateImu(
          {data.imu.front()}, start, start.t_ns, ImuBias(), kGravityW, IntegrationMethod::kEuler),
      Error);
}

// The seed's experiment [seed000 §2] on the course trajectory: noise-free, 20 s at 200 Hz.
TEST(IntegrateImu, MidpointBeatsEulerTenfoldAndRk4BeatsMidpointOnVioCourse) {
  const AnalyticData data = MakeAnalyticData(VioCourseTrajectory(), 200.0, 20.0);
  const double euler = FinalPositionError(data, IntegrationMethod::kEuler);
  const double midpoint = FinalPositionError(data, IntegrationMethod::kMidpoint);
  const double rk4 = FinalPositionError(data, IntegrationMethod::kRk4);
  std::printf(
      "vio_course 20 s @ 200 Hz final position error [m]: euler %.6g  midpoint %.6g  "
      "rk4 %.6g\n",
      euler,
      midpoint,
      rk4);
  EXPECT_LE(midpoint, euler / 10.0);
  EXPECT_LE(rk4, midpoint);
}

// Doubling the rate divides the error by 2^order. Position bounds: Euler order 1 (ratio 2),
// midpoint and RK4 order 2 (ratio 4; RK4 is limited by the linear interpolation of the
// accelerometer, see integrate.h). The ranges allow +-25% for the higher-order terms still
// present at 100 Hz.
TEST(IntegrateImu, ErrorsShrinkAtTheExpectedOrderWhenTheRateDoubles) {
  struct Expected {
    IntegrationMethod method;
    double min_ratio;
    double max_ratio;
  };
  const Expected expected[] = {{IntegrationMethod::kEuler, 1.6, 2.5},
                               {IntegrationMethod::kMidpoint, 3.2, 5.0},
                               {IntegrationMethod::kRk4, 3.2, 5.0}};
  for (const AnalyticTrajectory& trajectory : {VioCourseTrajectory(), Figure8Trajectory()}) {
    std::vector<AnalyticData> data;
    for (double rate_hz : {100.0, 200.0, 400.0}) {
      data.push_back(MakeAnalyticData(trajectory, rate_hz, 20.0));
    }
    for (const Expected& e : expected) {
      const double e100 = FinalPositionError(data[0], e.method);
      const double e200 = FinalPositionError(data[1], e.method);
      const double e400 = FinalPositionError(data[2], e.method);
      std::printf(
          "%s %s final position error [m] at 100/200/400 Hz: %.4g %.4g %.4g "
          "(ratios %.3f %.3f)\n",
          trajectory.name().c_str(),
          IntegrationMethodName(e.method),
          e100,
          e200,
          e400,
          e100 / e200,
          e200 / e400);
      EXPECT_GE(e100 / e200, e.min_ratio)
          << trajectory.name() << " " << IntegrationMethodName(e.method);
      EXPECT_LE(e100 / e200, e.max_ratio)
          << trajectory.name() << " " << IntegrationMethodName(e.method);
      EXPECT_GE(e200 / e400, e.min_ratio)
          << trajectory.name() << " " << IntegrationMethodName(e.method);
      EXPECT_LE(e200 / e400, e.max_ratio)
          << trajectory.name() << " " << IntegrationMethodName(e.method);
    }
    // Rotation: RK4 with the cubic mid-step gyro is order 4 (ratio 16), midpoint order 2.
    const double r100 = FinalRotationError(data[0], IntegrationMethod::kRk4);
    const double r200 = FinalRotationError(data[1], IntegrationMethod::kRk4);
    const double m200 = FinalRotationError(data[1], IntegrationMethod::kMidpoint);
    std::printf(
        "%s final rotation error [rad]: rk4 %.3g (100 Hz) %.3g (200 Hz), midpoint %.3g "
        "(200 Hz)\n",
        trajectory.name().c_str(),
        r100,
        r200,
        m200);
    EXPECT_GE(r100 / r200, 12.0) << trajectory.name();
    EXPECT_LT(r200, m200 / 100.0) << trajectory.name();
  }
}

TEST(InterpolateNavState, ExactAtSamplesAndForCubicMotion) {
  // p(t) = c0 + c1 t + c2 t^2 + c3 t^3 with v = p': the cubic Hermite interpolant is exact.
  const Eigen::Vector3d c0(1, 2, 3), c1(0.5, -1, 0.2), c2(0.1, 0.3, -0.4), c3(-0.05, 0.02, 0.1);
  const Eigen::Vector3d w(0.2, -0.1, 0.4);
  std::vector<NavState> trajectory;
  for (int k = 0; k <= 10; ++k) {
    const double t = 0.1 * k;
    NavState state;
    state.t_ns = k * 100'000'000;
    state.p_w_s = c0 + c1 * t + c2 * t * t + c3 * t * t * t;
    state.v_w = c1 + 2.0 * c2 * t + 3.0 * c3 * t * t;
    state.R_w_s = SO3d::Exp(w * t);
    trajectory.push_back(state);
  }
  const NavState at_sample = InterpolateNavState(trajectory, 300'000'000);
  EXPECT_EQ(at_sample.p_w_s, trajectory[3].p_w_s);
  const double t = 0.437;
  const NavState between = InterpolateNavState(trajectory, 437'000'000);
  EXPECT_LT((between.p_w_s - (c0 + c1 * t + c2 * t * t + c3 * t * t * t)).norm(), 1e-13);
  EXPECT_LT((between.R_w_s.inverse() * SO3d::Exp(w * t)).Log().norm(), 1e-13);
  EXPECT_THROW(InterpolateNavState(trajectory, 1'000'000'001), Error);
}

TEST(ComputeDrift, ZeroOnTheTruthAndExactForAKnownOffset) {
  const AnalyticData data = MakeAnalyticData(Figure8Trajectory(), 100.0, 5.0);
  std::vector<NavState> trajectory;
  for (const GroundTruthState& truth : data.truth) {
    trajectory.push_back(NavStateFromGroundTruth(truth));
  }
  DriftMetrics drift = ComputeDrift(trajectory, data.truth);
  EXPECT_EQ(drift.num_compared, static_cast<int64_t>(data.truth.size()));
  EXPECT_LT(drift.ate_rmse_m, 1e-12);
  EXPECT_LT(drift.final_rotation_error_deg, 1e-9);
  // A constant 3 cm offset and a 2 degree rotation about z at the end.
  for (NavState& state : trajectory) state.p_w_s += Eigen::Vector3d(0.0, 0.03, 0.0);
  trajectory.back().R_w_s = trajectory.back().R_w_s * SO3d::Exp(Eigen::Vector3d(0, 0, kPi / 90));
  drift = ComputeDrift(trajectory, data.truth);
  EXPECT_NEAR(drift.ate_rmse_m, 0.03, 1e-12);
  EXPECT_NEAR(drift.final_position_error_m, 0.03, 1e-12);
  EXPECT_NEAR(drift.final_rotation_error_deg, 2.0, 1e-9);
  EXPECT_EQ(drift.final_t_ns, data.truth.back().t_ns);
}

// Real data: EuRoC V1_01_easy, first 10 s from the ground-truth start state and biases. The
// drift of each method goes to docs/integrate.md (on real data all three methods drift about the
// same: sensor noise and the ground truth's own bias estimate dominate the discretisation error at
// 200 Hz). Over 10 s that drift (4 m) exceeds the motion (0.94 m), so a bound on it cannot tell
// dead reckoning from staying at the start. The checks therefore take their bounds from the
// data's own errors, measured while the MAV sits still (testing/static_phase.h), where nothing
// depends on the integrator:
//  - rotation after 10 s: a gyro bias error db_g turns the estimate by at most |db_g| T, plus the
//    ground truth's own orientation jitter (the largest angle it reports while still);
//  - position over 1 s windows started from the ground truth every 0.5 s: at most
//    dv T + (a_still + db_a + g dtheta) T^2 / 2, from the ground truth's velocity error dv (its
//    largest speed while still) and a constant acceleration error made of the world acceleration
//    the readings give while still (a_still), the largest change of the ground truth's
//    accelerometer bias inside the window (db_a: the integration holds it at the window's first
//    value) and its orientation jitter dtheta misprojecting gravity.
// Measured: dv 0.015 m/s, a_still 0.037 m/s^2, dtheta 0.18 deg (0.030 m/s^2), db_a up to 0.037
// m/s^2: window bounds 0.052-0.068 m, worst window error 0.032 m for every method; the ten
// windows from 4.5 s on move by 0.056-0.38 m, more than their bounds, so a trajectory that stays
// put fails, and so does one that drops the accelerometer bias (0.084 m). The rotation bound is
// 0.96 deg (1.4e-3 rad/s over 10 s, 0.18 deg), the errors 0.31-0.36 deg, the true rotation 75 deg.
TEST(IntegrateImu, EurocV101EasyFirstTenSeconds) {
  const std::string dir = testing::SharedDataDir() + "/euroc_v1_01_easy";
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_v1_01_easy/imu0.csv");
  const std::vector<ImuSample> imu = ReadEurocImu(dir + "/imu0.csv");
  const std::vector<GroundTruthState> truth = ReadEurocGroundTruth(dir + "/groundtruth.csv");
  const NavState start = NavStateFromGroundTruth(truth.front());
  const ImuBias bias = BiasFromGroundTruth(truth.front());
  constexpr double kDurationS = 10.0;
  const int64_t end_ns = start.t_ns + 10'000'000'000;

  const testing::StaticPhase still =
      testing::MeasureStaticPhase(imu, truth, testing::kV101StaticDurationNs);
  const double a_still = (still.mean_specific_force_w + kGravityW).norm();
  const double max_rotation_error_deg =
      (still.gyro_bias_error.norm() * kDurationS + still.max_rotation_rad) * kRadToDeg;
  std::printf(
      "still: |a| %.4f m/s^2, |db_g| %.2e rad/s, speed %.4f m/s, jitter %.3f deg; rotation "
      "bound %.3f deg\n",
      a_still,
      still.gyro_bias_error.norm(),
      still.max_speed_m_s,
      still.max_rotation_rad * kRadToDeg,
      max_rotation_error_deg);
  // 1 s windows from every tenth ground-truth row (every 0.5 s at 20 Hz) and their bounds.
  constexpr double kWindowS = 1.0;
  constexpr size_t kWindowRows = 20;
  std::vector<size_t> windows;
  std::vector<double> window_bounds_m;
  for (size_t k = 0; k + kWindowRows < truth.size() && truth[k + kWindowRows].t_ns <= end_ns;
       k += 10) {
    ASSERT_EQ(truth[k + kWindowRows].t_ns - truth[k].t_ns, 1'000'000'000);
    double accel_bias_change = 0.0;
    for (size_t i = k; i <= k + kWindowRows; ++i) {
      accel_bias_change =
          std::max(accel_bias_change, (truth[i].accel_bias - truth[k].accel_bias).norm());
    }
    const double a_error = a_still + accel_bias_change + kGravity * still.max_rotation_rad;
    windows.push_back(k);
    window_bounds_m.push_back(still.max_speed_m_s * kWindowS + 0.5 * a_error * kWindowS * kWindowS);
  }
  ASSERT_EQ(windows.size(), 19u);

  for (IntegrationMethod method : kAllMethods) {
    std::vector<NavState> trajectory;
    IntegrateImu(imu, start, end_ns, bias, kGravityW, method, &trajectory);
    const DriftMetrics drift = ComputeDrift(trajectory, truth);
    double worst_window_m = 0.0;
    for (size_t w = 0; w < windows.size(); ++w) {
      const GroundTruthState& first = truth[windows[w]];
      const GroundTruthState& last = truth[windows[w] + kWindowRows];
      const NavState state = IntegrateImu(imu,
                                          NavStateFromGroundTruth(first),
                                          last.t_ns,
                                          BiasFromGroundTruth(first),
                                          kGravityW,
                                          method);
      const double error_m = (state.p_w_s - last.p_w_s).norm();
      worst_window_m = std::max(worst_window_m, error_m);
      EXPECT_LT(error_m, window_bounds_m[w])
          << IntegrationMethodName(method) << ", window from "
          << (first.t_ns - start.t_ns) / 1'000'000 << " ms";
    }
    std::printf(
        "EuRoC V1_01_easy 10 s %-8s final position error %.4f m, final rotation error "
        "%.4f deg, ATE RMSE %.4f m (%lld poses); worst 1 s window %.4f m\n",
        IntegrationMethodName(method),
        drift.final_position_error_m,
        drift.final_rotation_error_deg,
        drift.ate_rmse_m,
        static_cast<long long>(drift.num_compared),
        worst_window_m);
    EXPECT_EQ(drift.final_t_ns, end_ns);
    EXPECT_LT(drift.final_rotation_error_deg, max_rotation_error_deg)
        << IntegrationMethodName(method);
  }
  std::printf("1 s window bounds %.4f-%.4f m\n",
              *std::min_element(window_bounds_m.begin(), window_bounds_m.end()),
              *std::max_element(window_bounds_m.begin(), window_bounds_m.end()));
}

}  // namespace
}  // namespace splinecal
