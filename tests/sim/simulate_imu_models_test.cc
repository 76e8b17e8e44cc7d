// The simulator through Kalibr's IMU models (sim/simulate_imu.h, imu/imu_intrinsic_model.h):
// several IMUs at their poses and clock offsets.
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <vector>

#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/lie/so3.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/report/simulate_report.h"
#include "splinecal/sim/simulation_result.h"
#include "splinecal/sim/trajectories.h"
#include "testing/consumer_imu.h"

namespace splinecal {
namespace {

// The model is applied to the spline's motion with the same arithmetic in both: rounding only.
constexpr double kRoundingTolerance = 1e-12;

const int64_t kKnotSpacingNs = 50'000'000;
const int64_t kStartNs = kKnotSpacingNs;
const int64_t kEndNs = kStartNs + 4'000'000'000;

const SE3Splined& CourseSpline() {
  static const SE3Splined* spline = new SE3Splined(
      FitAnalyticTrajectory(VioCourseTrajectory(), kStartNs, kEndNs + 1'000'000'000, kKnotSpacingNs)
          .MakeSpline());
  return *spline;
}

using testing::ConsumerImu;
using testing::MountedImu;

SimulationOptions NoiseFree(const ImuCalibration& imu) {
  SimulationOptions options;
  options.noise_free = true;
  options.gyro_bias = Eigen::Vector3d(0.01, -0.02, 0.005);
  options.accel_bias = Eigen::Vector3d(-0.1, 0.05, 0.2);
  options.imu = imu;
  return options;
}

// [gyro; accel] of `imu` for `motion` with the options' biases.
Eigen::Matrix<double, 6, 1> Predicted(const ImuCalibration& imu,
                                      const SimulationOptions& options,
                                      const BodyMotion<double>& motion) {
  Eigen::Vector3d gyro, accel;
  PredictImuReadings(imu.model,
                     imu.intrinsics,
                     motion,
                     options.gyro_bias,
                     options.accel_bias,
                     &gyro,
                     &accel,
                     nullptr,
                     nullptr);
  Eigen::Matrix<double, 6, 1> out;
  out << gyro, accel;
  return out;
}

class SimulateImuModel : public ::testing::TestWithParam<ImuModelKind> {};

// Every reading is the model's prediction of the spline's motion at its stamp + time offset,
// plus the biases: for the reference IMU and for a rotated, displaced, late one.
TEST_P(SimulateImuModel, ReadingsAreTheModelsPredictionOnTheSpline) {
  const SE3Splined& spline = CourseSpline();
  for (const ImuCalibration& imu : {ConsumerImu(GetParam()), MountedImu(GetParam())}) {
    const SimulationOptions options = NoiseFree(imu);
    std::vector<ImuSample> samples;
    SimulateImu(spline, kStartNs, kEndNs, options, &samples, nullptr);
    ASSERT_GT(samples.size(), 700u);
    const int64_t offset_ns = std::llround(imu.time_offset_s * 1e9);
    EXPECT_GE(samples.front().t_ns + offset_ns, kStartNs);
    EXPECT_LE(samples.back().t_ns + offset_ns, kEndNs);
    for (size_t k = 0; k < samples.size(); k += 37) {
      const BodyMotion<double> motion =
          SplineBodyMotion(spline, spline.SegmentAtNs(samples[k].t_ns + offset_ns), GravityWorld());
      const Eigen::Matrix<double, 6, 1> expected = Predicted(imu, options, motion);
      ASSERT_LT((samples[k].gyro - expected.head<3>()).cwiseAbs().maxCoeff(), kRoundingTolerance)
          << k;
      ASSERT_LT((samples[k].accel - expected.tail<3>()).cwiseAbs().maxCoeff(), kRoundingTolerance)
          << k;
    }
  }
}

// Against the closed-form trajectory (sim/trajectories.h) instead of the spline: the readings
// agree to the spline fit's derivative error (the bounds of FitAnalyticTrajectory's closed-form
// test, 1e-3 rad/s and 0.05 m/s^2); dw_s comes from central differences of the closed-form w_s
// (h = 1e-4 s: error ~h^2 |w'''| / 6 < 1e-8 rad/s^2).
TEST_P(SimulateImuModel, ReadingsFollowTheClosedFormTrajectory) {
  const SE3Splined& spline = CourseSpline();
  const ImuCalibration imu = MountedImu(GetParam());
  std::vector<ImuSample> samples;
  SimulateImu(spline, kStartNs, kEndNs, NoiseFree(imu), &samples, nullptr);
  const SimulationOptions options = NoiseFree(imu);
  const AnalyticTrajectory course = VioCourseTrajectory();
  constexpr double kStep = 1e-4;
  double gyro_error = 0.0, accel_error = 0.0;
  for (size_t k = 0; k < samples.size(); k += 11) {
    const double t = (samples[k].t_ns - kStartNs) * 1e-9 + imu.time_offset_s;
    const TrajectoryState state = course.Evaluate(t);
    BodyMotion<double> motion;
    motion.w_b = state.w_s;
    motion.dw_b = (course.Evaluate(t + kStep).w_s - course.Evaluate(t - kStep).w_s) / (2 * kStep);
    motion.f_b = state.T_w_s.so3().inverse() * (state.a_w - GravityWorld());
    const Eigen::Matrix<double, 6, 1> expected = Predicted(imu, options, motion);
    gyro_error = std::max(gyro_error, (samples[k].gyro - expected.head<3>()).norm());
    accel_error = std::max(accel_error, (samples[k].accel - expected.tail<3>()).norm());
  }
  EXPECT_LT(gyro_error, 1e-3);
  EXPECT_LT(accel_error, 0.05);
}

INSTANTIATE_TEST_SUITE_P(AllModels,
                         SimulateImuModel,
                         ::testing::Values(ImuModelKind::kCalibrated,
                                           ImuModelKind::kScaleMisalignment,
                                           ImuModelKind::kScaleMisalignmentSizeEffect));

// The default options are today's simulator: the calibrated model at the body origin.
TEST(SimulateImuModel, DefaultIsTheCalibratedModelAtTheBodyOrigin) {
  const SE3Splined& spline = CourseSpline();
  SimulationOptions plain = NoiseFree(ImuCalibration());
  SimulationOptions rotated = plain;
  // A model path with nominal values: the same readings up to rounding.
  rotated.imu.model = ImuModelKind::kScaleMisalignment;
  std::vector<ImuSample> a, b;
  SimulateImu(spline, kStartNs, kStartNs + 500'000'000, plain, &a, nullptr);
  SimulateImu(spline, kStartNs, kStartNs + 500'000'000, rotated, &b, nullptr);
  ASSERT_EQ(a.size(), b.size());
  for (size_t k = 0; k < a.size(); ++k) {
    EXPECT_EQ(a[k].t_ns, b[k].t_ns);
    EXPECT_LT((a[k].gyro - b[k].gyro).norm(), kRoundingTolerance);
    EXPECT_LT((a[k].accel - b[k].accel).norm(), kRoundingTolerance);
  }
}

// RunSimulation with further IMUs: each has its own readings, model and noise.
TEST(RunSimulation, SimulatesEveryMountedImu) {
  SimulationTrajectory trajectory;
  trajectory.name = "figure8";
  SimulationRun run;
  run.start_ns = kStartNs;
  run.end_ns = kStartNs + 2'000'000'000;
  run.knot_spacing_s = 0.05;
  run.options.imu = ConsumerImu(ImuModelKind::kScaleMisalignment);
  run.more_imus = {MountedImu(ImuModelKind::kCalibrated),
                   MountedImu(ImuModelKind::kScaleMisalignmentSizeEffect)};
  RunSimulation(trajectory, PoseFitOptions(), &run);
  ASSERT_EQ(run.more_imu.size(), 2u);
  EXPECT_EQ(run.imu.size(), 401u);
  for (const std::vector<ImuSample>& more : run.more_imu) {
    // 3 ms late: the last stamp whose motion is inside the range is 3 ms before the end.
    ASSERT_EQ(more.size(), 401u);
    EXPECT_EQ(more.front().t_ns, run.start_ns - 3'000'000);
  }
  // Different noise (their own seeds) and different models.
  EXPECT_NE(run.more_imu[0][10].gyro, run.more_imu[1][10].gyro);
  EXPECT_TRUE(HasImuModels(run));
}

}  // namespace
}  // namespace splinecal
