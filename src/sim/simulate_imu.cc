#include "splinecal/sim/simulate_imu.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>

#include "splinecal/error.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {
namespace {

// The calibrated model at the body's origin on the body's clock: the readings are formed as
// PredictImu forms them (bit for bit, see below), without the intrinsic model.
bool IsPlainImu(const ImuCalibration& imu) {
  const ImuIntrinsicsd nominal;
  return imu.model == ImuModelKind::kCalibrated && imu.time_offset_s == 0.0 &&
         imu.intrinsics.C_i_b == nominal.C_i_b && imu.intrinsics.r_b == nominal.r_b;
}

}  // namespace

std::vector<int64_t> ImuTimestamps(int64_t start_ns, int64_t end_ns, double rate_hz) {
  if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    throw Error("IMU rate must be finite and > 0 Hz, got " + std::to_string(rate_hz));
  }
  if (end_ns < start_ns) {
    throw Error("simulation end " + std::to_string(end_ns) + " ns is before its start " +
                std::to_string(start_ns) + " ns");
  }
  const double period_ns = 1e9 / rate_hz;
  const double count = std::floor(static_cast<double>(end_ns - start_ns) / period_ns) + 1.0;
  if (count > 1e9) {
    throw Error("simulation would produce " + std::to_string(count) +
                " IMU samples (more than 1e9): shorten the duration or lower the rate");
  }
  std::vector<int64_t> times;
  times.reserve(static_cast<size_t>(count) + 1);
  for (int64_t k = 0;; ++k) {
    const int64_t t_ns = start_ns + std::llround(static_cast<double>(k) * period_ns);
    if (t_ns > end_ns) break;
    if (!times.empty() && t_ns <= times.back()) {
      throw Error("IMU rate " + std::to_string(rate_hz) +
                  " Hz is too high for nanosecond timestamps");
    }
    times.push_back(t_ns);
  }
  return times;
}

void SimulateImu(const SE3Splined& spline,
                 int64_t start_ns,
                 int64_t end_ns,
                 const SimulationOptions& options,
                 std::vector<ImuSample>* imu,
                 std::vector<GroundTruthState>* ground_truth) {
  CHECK(imu != nullptr);
  if (start_ns < spline.start_time_ns() || end_ns > spline.end_time_ns()) {
    throw Error("simulation interval [" + std::to_string(start_ns) + ", " + std::to_string(end_ns) +
                "] ns is outside the spline's valid range [" +
                std::to_string(spline.start_time_ns()) + ", " +
                std::to_string(spline.end_time_ns()) + "] ns");
  }
  if (!std::isfinite(options.gravity_m_s2)) throw Error("gravity must be finite");
  if (!(std::abs(options.imu.time_offset_s) <= 1e6)) {
    throw Error("IMU time offset must be finite and within 1e6 s");
  }
  if (!options.gyro_bias.allFinite() || !options.accel_bias.allFinite()) {
    throw Error("initial IMU biases must be finite");
  }
  // The IMU's own clock: stamps t with t + offset inside [start_ns, end_ns].
  const int64_t offset_ns = std::llround(options.imu.time_offset_s * 1e9);
  const std::vector<int64_t> times =
      ImuTimestamps(start_ns - offset_ns, end_ns - offset_ns, options.imu_rate_hz);
  const bool plain_model = IsPlainImu(options.imu);
  std::unique_ptr<ImuNoiseGenerator> noise;
  if (!options.noise_free) {
    ImuNoise densities = options.noise;
    densities.update_rate_hz = options.imu_rate_hz;
    noise = std::make_unique<ImuNoiseGenerator>(
        densities, options.gyro_bias, options.accel_bias, options.seed);
  }
  const Eigen::Vector3d g_w(0.0, 0.0, -options.gravity_m_s2);

  // Every element is overwritten below: resize only (no clear), so a reused vector costs nothing.
  imu->resize(times.size());
  if (ground_truth != nullptr) ground_truth->resize(times.size());
  Eigen::Vector3d gyro_bias = options.gyro_bias;
  Eigen::Vector3d accel_bias = options.accel_bias;
  for (size_t k = 0; k < times.size(); ++k) {
    const Segment<double> segment = spline.SegmentAtNs(times[k] + offset_ns);
    SE3d T_w_s;
    Eigen::Matrix3d R_w_s;
    Eigen::Vector3d w_s, w_dot_s, v_s, a_s;
    // One pass for the readings and the ground truth. The reading is formed exactly as
    // PredictImu forms it (imu/imu_model.h): gyro = w_s (+ b_g), accel = a_s - R^T g_w (+ b_a),
    // a_s = R^T a_w, so the noise-free zero-bias output is bit-identical to PredictImu.
    internal::EvaluateSegmentBody(spline.model(),
                                  spline.Knots(segment),
                                  segment,
                                  ground_truth != nullptr ? &T_w_s : nullptr,
                                  &R_w_s,
                                  &w_s,
                                  plain_model ? nullptr : &w_dot_s,
                                  ground_truth != nullptr ? &v_s : nullptr,
                                  &a_s);
    ImuSample& sample = (*imu)[k];
    sample.t_ns = times[k];
    sample.gyro = w_s;
    sample.accel = a_s - R_w_s.transpose() * g_w;
    if (!plain_model) {
      BodyMotion<double> motion;
      motion.w_b = w_s;
      motion.dw_b = w_dot_s;
      motion.f_b = sample.accel;
      const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
      PredictImuReadings(options.imu.model,
                         options.imu.intrinsics,
                         motion,
                         zero,
                         zero,
                         &sample.gyro,
                         &sample.accel,
                         nullptr,
                         nullptr);
    }
    if (noise != nullptr) {
      noise->Corrupt(&sample, &gyro_bias, &accel_bias);
    } else {
      sample.gyro += gyro_bias;
      sample.accel += accel_bias;
    }
    if (ground_truth != nullptr) {
      GroundTruthState& truth = (*ground_truth)[k];
      truth.t_ns = times[k] + offset_ns;
      truth.p_w_s = T_w_s.translation();
      truth.q_w_s = T_w_s.so3().quaternion();
      truth.v_w = R_w_s * v_s;  // As EvaluateSegment forms v_w.
      truth.gyro_bias = gyro_bias;
      truth.accel_bias = accel_bias;
    }
  }
}

PoseFitResult FitAnalyticTrajectory(const AnalyticTrajectory& trajectory,
                                    int64_t start_ns,
                                    int64_t end_ns,
                                    int64_t knot_spacing_ns,
                                    int64_t pose_step_ns,
                                    const PoseFitOptions& options) {
  const KnotLayout layout = KnotLayoutCovering(start_ns, end_ns, knot_spacing_ns);
  if (pose_step_ns <= 0) pose_step_ns = std::max<int64_t>(1, knot_spacing_ns / 10);
  const int64_t valid_end_ns =
      layout.t0_ns + static_cast<int64_t>(layout.num_control_poses - 2) * layout.dt_ns;
  const std::vector<StampedPose> poses = trajectory.Sample(start_ns, valid_end_ns, pose_step_ns);
  return FitControlPoses(poses, layout, options);
}

}  // namespace splinecal
