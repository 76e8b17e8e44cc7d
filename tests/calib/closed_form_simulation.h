// Simulated data from a CLOSED-FORM trajectory (sim/trajectories.h's AnalyticTrajectory, sums of
// sinusoids in position and roll/pitch/yaw with exact derivatives) rather than from a spline.
//
// The simulator proper (sim/simulate_imu.h, sim/simulate_camera.h) predicts the IMU and the
// cameras from a spline fitted on the same knot layout the estimators use: their model is then
// exactly right, which real data never is. These helpers predict from the closed form itself, so
// the estimators' splines only approximate the motion (the Monte-Carlo NEES tests need that to
// say anything about real data):
//
//     gyro_k  = w_s(t_k) + b_g,k + n_g,k
//     accel_k = R_w_s(t_k)^T (a_w(t_k) - g_w) + b_a,k + n_a,k,      g_w = (0, 0, -g)
//
// with w_s, a_w the trajectory's analytic derivatives and the noise and bias random walk of
// sim/noise_generator.h; and each target corner exposed at t_frame + time_offset + tau with
// tau = line_delay * v(tau) (docs/conventions.md "Camera, time offset, rolling shutter"), solved by
// fixed-point iteration (the map's slope is line_delay * dv/dt, a few percent for real motion).
//
// Trajectory time: (t_ns - start_ns) * 1e-9 s, IMU clock. SimulationOptions::imu puts a further
// IMU of a rig at its pose T_i_b, clock offset and model: its reading stamped t is
// PredictImuReadings of the motion at t + time_offset (imu/imu_intrinsics.h).
#ifndef SPLINECAL_TESTS_CALIB_CLOSED_FORM_SIMULATION_H_
#define SPLINECAL_TESTS_CALIB_CLOSED_FORM_SIMULATION_H_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

// IMU readings at ImuTimestamps(start_ns, end_ns, options.imu_rate_hz) (file comment). With
// options.noise_free: the exact readings plus the initial biases.
inline std::vector<ImuSample> SimulateImuFromTrajectory(const AnalyticTrajectory& trajectory,
                                                        int64_t start_ns,
                                                        int64_t end_ns,
                                                        const SimulationOptions& options) {
  ImuNoise noise = options.noise;
  noise.update_rate_hz = options.imu_rate_hz;
  ImuNoiseGenerator generator(noise, options.gyro_bias, options.accel_bias, options.seed);
  const Eigen::Vector3d g_w(0.0, 0.0, -options.gravity_m_s2);
  // options.imu at its default (the reference IMU) keeps the readings above bit for bit.
  const ImuIntrinsicsd nominal;
  const bool at_origin = options.imu.model == ImuModelKind::kCalibrated &&
                         options.imu.time_offset_s == 0.0 &&
                         options.imu.intrinsics.C_i_b == nominal.C_i_b &&
                         options.imu.intrinsics.r_b == nominal.r_b;
  std::vector<ImuSample> imu;
  for (int64_t t_ns : ImuTimestamps(start_ns, end_ns, options.imu_rate_hz)) {
    const double t_s = 1e-9 * static_cast<double>(t_ns - start_ns) + options.imu.time_offset_s;
    const TrajectoryState state = trajectory.Evaluate(t_s);
    ImuSample sample;
    sample.t_ns = t_ns;
    sample.gyro = state.w_s;
    sample.accel = state.T_w_s.so3().inverse() * (state.a_w - g_w);
    if (!at_origin) {
      // The IMU at options.imu's pose, clock offset and model (imu/imu_intrinsic_model.h). dw_b
      // by central differences of the exact w_b with h = 1e-5 s: truncation h^2 |d3w/dt3| / 6 <
      // 1e-8 rad/s^2 for periods >= 0.8 s and rates <= 2 rad/s, rounding ~1e-16 x 2 / h = 2e-11:
      // far below the gyro's noise (~1e-3 rad/s per sample) times any lever arm here.
      constexpr double kH = 1e-5;
      BodyMotion<double> motion;
      motion.w_b = state.w_s;
      motion.dw_b = (trajectory.Evaluate(t_s + kH).w_s - trajectory.Evaluate(t_s - kH).w_s) /
                    (2.0 * kH);
      motion.f_b = sample.accel;
      PredictImuReadings<double>(options.imu.model, options.imu.intrinsics, motion,
                                 Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &sample.gyro,
                                 &sample.accel);
    }
    if (options.noise_free) {
      sample.gyro += options.gyro_bias;
      sample.accel += options.accel_bias;
    } else {
      generator.Corrupt(&sample, nullptr, nullptr);
    }
    imu.push_back(sample);
  }
  return imu;
}

// The corners of options.target (options.has_target must be set; landmarks are not simulated)
// seen by camera `cam` (cam_id 0) riding on the trajectory, frames at options.camera_rate_hz from
// start_ns - time_offset (camera clock) while the whole readout stays before end_ns. The
// visibility checks and the noise are those of sim/simulate_camera.h.
inline CameraSimulationResult SimulateTargetFromTrajectory(const AnalyticTrajectory& trajectory,
                                                           int64_t start_ns,
                                                           int64_t end_ns,
                                                           const CameraCalibration& cam,
                                                           const CameraSimulationOptions& options) {
  constexpr int kMaxIterations = 50;
  constexpr double kToleranceS = 1e-13;
  CameraSimulationResult result;
  GaussianSampler noise(options.seed);
  const SE3d T_imu_cam = cam.T_cam_imu.inverse();
  const double tau_max = cam.line_delay_s * (cam.camera.height - 1);
  const int64_t shift_ns = std::llround(cam.time_offset_s * 1e9);
  const int64_t readout_ns = static_cast<int64_t>(std::ceil(tau_max * 1e9));
  const double cos_max_view = std::cos(options.max_view_angle_deg * kPi / 180.0);
  for (int64_t k = 0;; ++k) {
    const int64_t t_cam_ns =
        start_ns - shift_ns + std::llround(static_cast<double>(k) * 1e9 / options.camera_rate_hz);
    if (t_cam_ns + shift_ns + readout_ns + 1 > end_ns) break;
    ++result.num_frames;
    // Exposure base time in trajectory seconds (IMU clock).
    const double t_base_s = 1e-9 * static_cast<double>(t_cam_ns - start_ns) + cam.time_offset_s;
    bool saw_target = false;
    for (const auto& [id, p_t] : options.target.points) {
      const Eigen::Vector3d p_w = options.T_w_t * p_t;
      // The camera pose and the point in it at exposure delay tau.
      auto camera_at = [&](double tau, SE3d* T_w_c, Eigen::Vector3d* p_c) {
        *T_w_c = trajectory.Pose(t_base_s + tau) * T_imu_cam;
        *p_c = T_w_c->inverse() * p_w;
      };
      double tau = 0.5 * tau_max;
      SE3d T_w_c;
      Eigen::Vector3d p_c;
      Eigen::Vector2d uv;
      bool projected = false;
      for (int iteration = 0; iteration < kMaxIterations; ++iteration) {
        camera_at(tau, &T_w_c, &p_c);
        projected = cam.camera.Project(p_c, &uv);
        if (!projected) break;
        const double next = cam.line_delay_s * uv.y();
        if (std::abs(next - tau) < kToleranceS) break;
        tau = std::clamp(next, 0.0, tau_max);
      }
      if (!projected || !(p_c.norm() >= options.min_depth_m) ||
          !(p_c.norm() <= options.max_depth_m)) {
        continue;
      }
      if (!cam.camera.IsDistortionMonotonic(p_c)) continue;
      if (!cam.camera.InImage(uv)) continue;
      // The exposure solved (not clamped): the pixel's row is the one exposed at tau.
      if (std::abs(cam.line_delay_s * uv.y() - tau) > 1e-9) continue;
      const SE3d T_t_c = options.T_w_t.inverse() * T_w_c;
      if (!(T_t_c.translation().z() > 0.0)) continue;
      if ((T_t_c.translation() - p_t).normalized().z() < cos_max_view) continue;
      Eigen::Vector2d pixel_noise = Eigen::Vector2d::Zero();  // u's draw first, then v's
      if (options.pixel_noise_px > 0.0) {
        pixel_noise.x() = options.pixel_noise_px * noise.Next();
        pixel_noise.y() = options.pixel_noise_px * noise.Next();
      }
      result.observations.push_back({t_cam_ns, 0, id, uv + pixel_noise});
      ++result.num_target_observations;
      saw_target = true;
    }
    if (saw_target) ++result.num_frames_with_target;
  }
  SortObservations(&result.observations);
  return result;
}

// Pose-source samples T_w_m = T_w_s T_m_s^-1 of the trajectory every step_ns over
// [start_ns, end_ns] (IMU clock), stamped in the pose clock t_pose = t_imu - time_offset_s, the
// world rotated by R_world, each perturbed (when sigma > 0) by N(0, sigma_m^2) in position and
// Exp(N(0, sigma_rad^2)) on the right in rotation.
struct PoseSourceOptions {
  int64_t step_ns = 50'000'000;
  double time_offset_s = 0.0;
  SE3d T_m_s;
  SO3d R_world;
  double sigma_m = 0.0;
  double sigma_rad = 0.0;
  uint64_t seed = 1;
};

inline std::vector<StampedPose> SamplePoseSource(const AnalyticTrajectory& trajectory,
                                                 int64_t start_ns,
                                                 int64_t end_ns,
                                                 const PoseSourceOptions& options) {
  GaussianSampler gaussian(options.seed);
  const SE3d T_world(options.R_world, Eigen::Vector3d::Zero());
  const SE3d T_s_m = options.T_m_s.inverse();
  const int64_t offset_ns = std::llround(options.time_offset_s * 1e9);
  std::vector<StampedPose> poses;
  for (int64_t t = start_ns; t <= end_ns; t += options.step_ns) {
    SE3d T_w_m = T_world * trajectory.Pose(1e-9 * static_cast<double>(t - start_ns)) * T_s_m;
    Eigen::Vector3d dp;
    Eigen::Vector3d dphi;
    for (int a = 0; a < 3; ++a) dp[a] = options.sigma_m * gaussian.Next();
    for (int a = 0; a < 3; ++a) dphi[a] = options.sigma_rad * gaussian.Next();
    T_w_m = SE3d(T_w_m.so3() * SO3d::Exp(dphi), T_w_m.translation() + dp);
    poses.push_back({t - offset_ns, T_w_m.translation(), T_w_m.so3().quaternion()});
  }
  return poses;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_CLOSED_FORM_SIMULATION_H_
