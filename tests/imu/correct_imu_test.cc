// Applying a calibration to raw readings (imu/correct_imu.h) on readings simulated through each
// model: the true angular velocity and specific force of the IMU come back.
#include "splinecal/imu/correct_imu.h"

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/lie/so3.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "testing/consumer_imu.h"

namespace splinecal {
namespace {

const int64_t kKnotSpacingNs = 50'000'000;
const int64_t kStartNs = kKnotSpacingNs;
const int64_t kEndNs = kStartNs + 10'000'000'000;

// A random trajectory with body rates up to 3 rad/s and accelerations up to 5 m/s^2: lively
// enough for the size effect's centripetal terms to matter (3^2 rad^2/s^2 x 6 mm = 0.05 m/s^2).
const SE3Splined& LivelySpline() {
  static const SE3Splined* spline = [] {
    RandomTrajectoryOptions options;
    options.max_angular_rate_rad_s = 3.0;
    options.max_acceleration_m_s2 = 5.0;
    options.min_period_s = 1.0;
    options.max_period_s = 5.0;
    return new SE3Splined(
        FitAnalyticTrajectory(
            RandomTrajectory(7, options), kStartNs, kEndNs + 1'000'000'000, kKnotSpacingNs)
            .MakeSpline());
  }();
  return *spline;
}

ImuCalibration ConsumerImu(ImuModelKind model) {
  ImuCalibration imu = testing::MountedImu(model);
  imu.time_offset_s = 0.0;  // correct keeps the IMU's stamps: compare on one clock
  return imu;
}

struct Truth {
  std::vector<Eigen::Vector3d> w_i, f_i;
};

// What an ideal IMU at the IMU's origin reads: C_i_b w_b and C_i_b f_b(r_b).
Truth TrueReadings(const ImuCalibration& imu, const std::vector<ImuSample>& samples) {
  const SE3Splined& spline = LivelySpline();
  Truth truth;
  for (const ImuSample& s : samples) {
    const BodyMotion<double> m =
        SplineBodyMotion(spline, spline.SegmentAtNs(s.t_ns), GravityWorld());
    truth.w_i.push_back(imu.intrinsics.C_i_b * m.w_b);
    truth.f_i.push_back(imu.intrinsics.C_i_b * SpecificForceAtPoint(m, imu.intrinsics.r_b));
  }
  return truth;
}

// RMS over the samples (the first and last h skipped: one-sided derivative windows) of the
// difference per axis.
Eigen::Vector3d RmsError(const std::vector<ImuSample>& out,
                         const std::vector<Eigen::Vector3d>& truth,
                         bool gyro) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (size_t k = 2; k + 2 < out.size(); ++k) {
    sum += ((gyro ? out[k].gyro : out[k].accel) - truth[k]).cwiseAbs2();
  }
  return (sum / (out.size() - 4.0)).cwiseSqrt();
}

// Readings of `imu` simulated with `sim` on the lively spline, corrected with the simulated
// (constant) biases, and the truth.
struct CorrectionRun {
  std::vector<ImuSample> raw, out;
  Truth truth;
};

CorrectionRun SimulateAndCorrect(const ImuCalibration& imu, SimulationOptions sim) {
  sim.imu = imu;
  CorrectionRun run;
  SimulateImu(LivelySpline(), kStartNs, kEndNs, sim, &run.raw, nullptr);
  ImuCorrectionOptions options;
  options.gyro_bias = sim.gyro_bias;
  options.accel_bias = sim.accel_bias;
  run.out = CorrectImuReadings(imu, run.raw, options);
  run.truth = TrueReadings(imu, run.raw);
  return run;
}

class CorrectImu : public ::testing::TestWithParam<ImuModelKind> {};

// Noise-free readings with constant biases: the model inverted exactly, up to the size effect's
// smoothed derivative (slope over 5 samples at 200 Hz: error ~h^2 |w'''| ~ 1e-4 rad/s^2, times
// millimetre arms ~1e-6 m/s^2).
TEST_P(CorrectImu, NoiseFreeReadingsGiveTheTrueRatesAndForces) {
  const ImuCalibration imu = ConsumerImu(GetParam());
  SimulationOptions sim;
  sim.noise_free = true;
  sim.gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.005);
  sim.accel_bias = Eigen::Vector3d(-0.1, 0.05, 0.2);
  const CorrectionRun run = SimulateAndCorrect(imu, sim);
  const std::vector<ImuSample>& out = run.out;
  const Truth& truth = run.truth;
  const bool size_effect = GetParam() == ImuModelKind::kScaleMisalignmentSizeEffect;
  EXPECT_LT(RmsError(out, truth.w_i, true).maxCoeff(), size_effect ? 1e-8 : 1e-12);
  EXPECT_LT(RmsError(out, truth.f_i, false).maxCoeff(), size_effect ? 1e-5 : 1e-12);
  // The raw readings are far from it (the model's percent errors and the biases): the test can
  // tell a correction from none.
  EXPECT_GT(RmsError(run.raw, truth.f_i, false).maxCoeff(), 1e-3);
}

// With white noise the corrected readings differ from the truth by the noise (M ~ I passes it
// almost unchanged): RMS per axis within 10% of the per-sample std (2000 samples: the RMS of
// Gaussian noise is within 3 of its 1.6% relative std), the size effect's derivative noise
// (~0.15 rad/s^2 x 6 mm ~ 1e-3 m/s^2) small beside 0.028 m/s^2.
TEST_P(CorrectImu, NoisyReadingsComeBackToTheNoiseLevel) {
  const ImuCalibration imu = ConsumerImu(GetParam());
  SimulationOptions sim;
  sim.noise.gyroscope_random_walk = 0.0;  // constant biases: the ones correct subtracts
  sim.noise.accelerometer_random_walk = 0.0;
  sim.gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.005);
  sim.accel_bias = Eigen::Vector3d(-0.1, 0.05, 0.2);
  sim.seed = 3;
  const CorrectionRun run = SimulateAndCorrect(imu, sim);
  const std::vector<ImuSample>& out = run.out;
  const Truth& truth = run.truth;
  const double gyro_std = sim.noise.GyroWhiteStd(sim.imu_rate_hz);
  const double accel_std = sim.noise.AccelWhiteStd(sim.imu_rate_hz);
  const Eigen::Vector3d gyro_rms = RmsError(out, truth.w_i, true);
  const Eigen::Vector3d accel_rms = RmsError(out, truth.f_i, false);
  std::printf(
      "correct %s: RMS error gyro [%.3g %.3g %.3g] rad/s (white std %.3g), accel "
      "[%.3g %.3g %.3g] m/s^2 (white std %.3g)\n",
      ImuModelName(GetParam()),
      gyro_rms(0),
      gyro_rms(1),
      gyro_rms(2),
      gyro_std,
      accel_rms(0),
      accel_rms(1),
      accel_rms(2),
      accel_std);
  for (int axis = 0; axis < 3; ++axis) {
    EXPECT_NEAR(gyro_rms(axis), gyro_std, 0.1 * gyro_std) << axis;
    EXPECT_NEAR(accel_rms(axis), accel_std, 0.1 * accel_std) << axis;
  }
}

INSTANTIATE_TEST_SUITE_P(AllModels,
                         CorrectImu,
                         ::testing::Values(ImuModelKind::kCalibrated,
                                           ImuModelKind::kScaleMisalignment,
                                           ImuModelKind::kScaleMisalignmentSizeEffect));

TEST(SmoothedDerivative, IsExactOnLinesAndUsesTheStamps) {
  std::vector<ImuSample> samples(7);
  std::vector<Eigen::Vector3d> values(7);
  const int64_t stamps[7] = {
      0, 5'000'000, 11'000'000, 15'000'000, 20'000'000, 26'000'000, 30'000'000};
  for (int k = 0; k < 7; ++k) {
    samples[k].t_ns = 1'403'715'273'262'142'976 + stamps[k];
    values[k] = Eigen::Vector3d(1.0, -2.0, 0.5) * (stamps[k] * 1e-9) + Eigen::Vector3d(3, 4, 5);
  }
  for (const Eigen::Vector3d& d : SmoothedDerivative(samples, values, 2)) {
    EXPECT_LT((d - Eigen::Vector3d(1.0, -2.0, 0.5)).norm(), 1e-9);
  }
}

TEST(CorrectImuReadings, RefusesSingularMatricesAndUnsortedStamps) {
  ImuCalibration imu = ConsumerImu(ImuModelKind::kScaleMisalignment);
  std::vector<ImuSample> raw(3);
  raw[1].t_ns = 5;
  raw[2].t_ns = 10;
  EXPECT_NO_THROW(CorrectImuReadings(imu, raw));
  imu.intrinsics.M_g(1, 1) = 0.0;
  EXPECT_THROW(CorrectImuReadings(imu, raw), Error);
  imu = ConsumerImu(ImuModelKind::kScaleMisalignment);
  raw[2].t_ns = 5;
  EXPECT_THROW(CorrectImuReadings(imu, raw), Error);
}

}  // namespace
}  // namespace splinecal
