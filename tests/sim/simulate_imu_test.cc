#include "splinecal/sim/simulate_imu.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/sim/trajectories.h"

namespace splinecal {
namespace {

// Ground-truth velocity against a central difference of the spline's positions, step h = 1 ms:
// truncation h^2/6 |p'''| (~3e-6 for |p'''| <= 20 m/s^3) plus rounding eps |p| / h (~1e-11).
constexpr double kVelocityDifferenceTolerance = 1e-5;
// The white-noise bound (docs/simulate.md, "Checks"): the per-sample std within 2%.
constexpr double kWhiteStdRelTolerance = 0.02;

const int64_t kKnotSpacingNs = 50'000'000;
const int64_t kStartNs = kKnotSpacingNs;  // spline.csv then starts at t0 = 0

// The course spline for the first `seconds` (shared by the tests; the fit takes ~0.1 s per 10 s).
const SE3Splined& CourseSpline(int seconds) {
  static std::map<int, SE3Splined>* cache = new std::map<int, SE3Splined>();
  auto it = cache->find(seconds);
  if (it == cache->end()) {
    const PoseFitResult fit = FitAnalyticTrajectory(VioCourseTrajectory(),
                                                    kStartNs,
                                                    kStartNs + seconds * int64_t{1'000'000'000},
                                                    kKnotSpacingNs);
    it = cache->emplace(seconds, fit.MakeSpline()).first;
  }
  return it->second;
}

// What SimulateImu writes: the readings and the ground truth at their times.
struct Simulation {
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
};

Simulation Simulate(const SE3Splined& spline,
                    int64_t start_ns,
                    int64_t end_ns,
                    const SimulationOptions& options) {
  Simulation out;
  SimulateImu(spline, start_ns, end_ns, options, &out.imu, &out.truth);
  return out;
}

// No noise, no bias: the readings are the spline's prediction.
SimulationOptions NoiseFree() {
  SimulationOptions options;
  options.noise_free = true;
  return options;
}

TEST(ImuTimestamps, ExactPeriodsAndNoAccumulatedDrift) {
  const std::vector<int64_t> t200 = ImuTimestamps(1'000, 1'000 + 1'000'000'000, 200.0);
  ASSERT_EQ(t200.size(), 201u);
  for (size_t k = 0; k < t200.size(); ++k) EXPECT_EQ(t200[k], 1'000 + int64_t(k) * 5'000'000);
  const std::vector<int64_t> t300 = ImuTimestamps(0, 10'000'000'000, 300.0);
  ASSERT_EQ(t300.size(), 3001u);
  EXPECT_EQ(t300[1], 3'333'333);
  EXPECT_EQ(t300[2], 6'666'667);
  EXPECT_EQ(t300.back(), 10'000'000'000);
  EXPECT_THROW(ImuTimestamps(0, 10, 0.0), Error);
  EXPECT_THROW(ImuTimestamps(0, 10, std::nan("")), Error);
  EXPECT_THROW(ImuTimestamps(10, 0, 200.0), Error);
}

TEST(SimulateImu, NoiseFreeZeroBiasIsExactlyTheSplinePrediction) {
  const SE3Splined& spline = CourseSpline(5);
  const auto [imu, truth] =
      Simulate(spline, spline.start_time_ns(), spline.end_time_ns(), NoiseFree());
  ASSERT_EQ(imu.size(), 1001u);
  const Eigen::Vector3d g_w = GravityWorld(9.81);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  for (const ImuSample& sample : imu) {
    const Segment<double> segment = spline.SegmentAtNs(sample.t_ns);
    Eigen::Vector3d gyro, accel;
    PredictImu(spline, segment, g_w, zero, zero, &gyro, &accel);
    ASSERT_EQ(sample.gyro, gyro) << "t = " << sample.t_ns;
    ASSERT_EQ(sample.accel, accel) << "t = " << sample.t_ns;
  }
  EXPECT_EQ(truth.front().gyro_bias, zero);
  EXPECT_EQ(truth.back().accel_bias, zero);
}

TEST(SimulateImu, GroundTruthIsTheSplinePoseAndItsDerivative) {
  const SE3Splined& spline = CourseSpline(5);
  SimulationOptions options;
  options.seed = 3;
  const auto [imu, truth] = Simulate(
      spline, spline.start_time_ns() + 2'000'000, spline.end_time_ns() - 2'000'000, options);
  ASSERT_EQ(truth.size(), imu.size());
  const int64_t h_ns = 1'000'000;
  for (size_t k = 0; k < truth.size(); k += 7) {
    const GroundTruthState& row = truth[k];
    EXPECT_EQ(row.t_ns, imu[k].t_ns);
    const Segment<double> segment = spline.SegmentAtNs(row.t_ns);
    SE3d T_w_s;
    Eigen::Vector3d v_w;
    spline.Evaluate(segment, &T_w_s, nullptr, nullptr, &v_w, nullptr);
    EXPECT_LT((row.p_w_s - T_w_s.translation()).norm(), 1e-12);
    EXPECT_LT(row.q_w_s.angularDistance(T_w_s.so3().quaternion()), 1e-12);
    EXPECT_LT((row.v_w - v_w).norm(), 1e-12);
    const Eigen::Vector3d v_numeric = (spline.PoseNs(row.t_ns + h_ns).translation() -
                                       spline.PoseNs(row.t_ns - h_ns).translation()) /
                                      (2e-9 * h_ns);
    EXPECT_LT((row.v_w - v_numeric).norm(), kVelocityDifferenceTolerance) << "t = " << row.t_ns;
  }
}

TEST(SimulateImu, ReadingsCarryTheReportedBiasesAndWhiteNoiseOfTheRightSize) {
  const SE3Splined& spline = CourseSpline(20);
  SimulationOptions options;
  options.seed = 11;
  options.gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.03);
  options.accel_bias = Eigen::Vector3d(0.1, 0.2, -0.3);
  options.noise.gyroscope_noise_density = 5e-3;  // Large enough to dominate rounding.
  const auto [noisy, truth] =
      Simulate(spline, spline.start_time_ns(), spline.end_time_ns(), options);
  const std::vector<ImuSample> clean =
      Simulate(spline, spline.start_time_ns(), spline.end_time_ns(), NoiseFree()).imu;
  ASSERT_EQ(noisy.size(), clean.size());
  EXPECT_EQ(truth.front().gyro_bias, options.gyro_bias);
  EXPECT_EQ(truth.front().accel_bias, options.accel_bias);
  EXPECT_NE(truth.back().gyro_bias, options.gyro_bias);  // It walked.
  Eigen::Array3d gyro_sum2 = Eigen::Array3d::Zero(), accel_sum2 = Eigen::Array3d::Zero();
  for (size_t k = 0; k < noisy.size(); ++k) {
    gyro_sum2 += (noisy[k].gyro - clean[k].gyro - truth[k].gyro_bias).array().square();
    accel_sum2 += (noisy[k].accel - clean[k].accel - truth[k].accel_bias).array().square();
  }
  const double n = static_cast<double>(noisy.size());  // 4001 samples: std error 1.1%
  const double gyro_expected = options.noise.gyroscope_noise_density * std::sqrt(200.0);
  const double accel_expected = options.noise.accelerometer_noise_density * std::sqrt(200.0);
  for (int i = 0; i < 3; ++i) {
    EXPECT_NEAR(std::sqrt(gyro_sum2[i] / n) / gyro_expected, 1.0, 2.5 * kWhiteStdRelTolerance);
    EXPECT_NEAR(std::sqrt(accel_sum2[i] / n) / accel_expected, 1.0, 2.5 * kWhiteStdRelTolerance);
  }
}

TEST(SimulateImu, SameSeedGivesTheSameBytes) {
  const SE3Splined& spline = CourseSpline(5);
  auto run = [&](uint64_t seed) {
    SimulationOptions options;
    options.seed = seed;
    options.gyro_bias = Eigen::Vector3d(0.001, 0.002, 0.003);
    const auto [imu, truth] =
        Simulate(spline, spline.start_time_ns(), spline.end_time_ns(), options);
    std::vector<double> values;
    for (size_t k = 0; k < imu.size(); ++k) {
      for (int i = 0; i < 3; ++i) {
        values.insert(values.end(),
                      {imu[k].gyro[i],
                       imu[k].accel[i],
                       truth[k].gyro_bias[i],
                       truth[k].accel_bias[i],
                       truth[k].p_w_s[i]});
      }
    }
    return values;
  };
  const std::vector<double> a = run(5);
  const std::vector<double> b = run(5);
  const std::vector<double> c = run(6);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(double)), 0);
  EXPECT_NE(std::memcmp(a.data(), c.data(), a.size() * sizeof(double)), 0);
}

TEST(SimulateImu, RejectsAnIntervalOutsideTheSpline) {
  const SE3Splined& spline = CourseSpline(5);
  std::vector<ImuSample> imu;
  SimulationOptions options;
  EXPECT_THROW(
      SimulateImu(spline, spline.start_time_ns() - 1, spline.end_time_ns(), options, &imu, nullptr),
      Error);
  EXPECT_THROW(
      SimulateImu(spline, spline.start_time_ns(), spline.end_time_ns() + 1, options, &imu, nullptr),
      Error);
  options.imu_rate_hz = -1.0;
  EXPECT_THROW(
      SimulateImu(spline, spline.start_time_ns(), spline.end_time_ns(), options, &imu, nullptr),
      Error);
}

TEST(FitAnalyticTrajectory, CourseSplineFollowsTheClosedForms) {
  // The spline is fitted to poses; its derivatives approximate the trajectory's: the IMU
  // readings agree with the closed forms to the cubic spline's O(dt^2) derivative error
  // (dt^2/12 |p''''| ~ 0.02 m/s^2 for z = sin(pi t); rates ~1e-4 rad/s).
  const int64_t end_ns = kStartNs + 20'000'000'000;
  const PoseFitResult fit =
      FitAnalyticTrajectory(VioCourseTrajectory(), kStartNs, end_ns, kKnotSpacingNs);
  std::printf("vio_course spline fit: position RMS %.3g m, rotation RMS %.3g deg (%lld poses)\n",
              fit.position_rms_m,
              fit.rotation_rms_deg,
              static_cast<long long>(fit.num_poses));
  EXPECT_LT(fit.position_rms_m, 1e-5);
  EXPECT_LT(fit.rotation_rms_deg, 1e-4);
  const SE3Splined spline = fit.MakeSpline();
  EXPECT_EQ(spline.t0_ns(), 0);
  EXPECT_EQ(spline.start_time_ns(), kStartNs);
  EXPECT_GE(spline.end_time_ns(), end_ns);
  const std::vector<ImuSample> imu = Simulate(spline, kStartNs, end_ns, NoiseFree()).imu;
  double gyro_error = 0.0, accel_error = 0.0;
  for (const ImuSample& sample : imu) {
    const TrajectoryState state = VioCourseTrajectory().Evaluate((sample.t_ns - kStartNs) * 1e-9);
    gyro_error = std::max(gyro_error, (sample.gyro - state.w_s).norm());
    const Eigen::Vector3d accel =
        state.T_w_s.so3().inverse() * (state.a_w - Eigen::Vector3d(0.0, 0.0, -9.81));
    accel_error = std::max(accel_error, (sample.accel - accel).norm());
  }
  std::printf(
      "vio_course spline vs closed form: max gyro error %.3g rad/s, max accel error "
      "%.3g m/s^2\n",
      gyro_error,
      accel_error);
  EXPECT_LT(gyro_error, 1e-3);
  EXPECT_LT(accel_error, 0.05);
}

// The seed's experiment [seed000 §2] end to end: simulate noise-free 20 s at 200 Hz on
// vio_course from the spline, integrate from the ground-truth start.
TEST(SimulateImu, MidpointBeatsEulerTenfoldOnSimulatedVioCourse) {
  const SE3Splined& spline = CourseSpline(20);
  const auto [imu, truth] = Simulate(spline, kStartNs, kStartNs + 20'000'000'000, NoiseFree());
  double error[3];
  int m = 0;
  for (IntegrationMethod method :
       {IntegrationMethod::kEuler, IntegrationMethod::kMidpoint, IntegrationMethod::kRk4}) {
    std::vector<NavState> trajectory;
    IntegrateImu(imu,
                 NavStateFromGroundTruth(truth.front()),
                 imu.back().t_ns,
                 ImuBias(),
                 GravityWorld(9.81),
                 method,
                 &trajectory);
    const DriftMetrics drift = ComputeDrift(trajectory, truth);
    std::printf(
        "simulated vio_course 20 s @ 200 Hz %-8s final position error %.4g m, rotation "
        "%.4g deg, ATE RMSE %.4g m\n",
        IntegrationMethodName(method),
        drift.final_position_error_m,
        drift.final_rotation_error_deg,
        drift.ate_rmse_m);
    error[m++] = drift.final_position_error_m;
  }
  EXPECT_LE(error[1], error[0] / 10.0);
  EXPECT_LE(error[2], error[1]);
}

}  // namespace
}  // namespace splinecal
