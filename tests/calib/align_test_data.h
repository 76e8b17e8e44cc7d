// Simulated inputs for the alignment tests and benchmark (header-only, test code).
//
// IMU readings are the exact derivatives of an analytic trajectory (sim/trajectories.h) at
// `imu_rate_hz`. The TRUE states at the camera frames are then either
//   * kDiscrete: the world trajectory obtained by integrating those very readings with the
//     midpoint scheme of vio/preintegration.h, written out here independently in the world
//     frame. Preintegration is then exact, so an alignment must recover scale, gravity and gyro
//     bias to rounding ("noise-free" in the model's sense), or
//   * kContinuous: the analytic trajectory itself (what a real IMU sees); the midpoint scheme's
//     O(h^2) error is then the only inconsistency.
// Camera poses are T_c0_c = T_w_c0^-1 T_w_c with T_w_c = T_w_s T_cam_imu^-1, positions divided by
// the scale (monocular, up to scale), optionally with pose noise.
#ifndef SPLINECAL_TESTS_CALIB_ALIGN_TEST_DATA_H_
#define SPLINECAL_TESTS_CALIB_ALIGN_TEST_DATA_H_

#include <Eigen/Core>
#include <cstdint>
#include <random>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace testing {

enum class Truth { kDiscrete, kContinuous };

struct ScenarioOptions {
  double duration_s = 10.0;
  double imu_rate_hz = 200.0;
  int imu_samples_per_frame = 20;          // camera at imu_rate / this (10 Hz)
  int64_t start_ns = 1403715273000000000;  // EuRoC-like epoch
  double trajectory_start_s = 0.0;         // where in the analytic trajectory to start
  Truth truth = Truth::kDiscrete;
  double scale = 0.37;  // metric = scale * camera positions
  double gravity = 9.81;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d(0.004, -0.003, 0.002);
  SE3d T_cam_imu;
  // Noise: IMU (Kalibr densities, 0 = none) and camera poses (per frame, per axis).
  bool imu_noise = false;
  ImuNoise noise;
  double camera_rotation_std_rad = 0.0;
  double camera_translation_std_m = 0.0;  // metric
  uint64_t seed = 1;
};

struct Scenario {
  std::vector<ImuSample> imu;
  std::vector<StampedPose> camera_poses;  // T_c0_c, up to scale
  // Truth.
  double scale = 0.0;
  Eigen::Vector3d gravity_c0 = Eigen::Vector3d::Zero();
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();  // the constant part
  SE3d T_cam_imu;
  SO3d R_w_c0;
  std::vector<SE3d> T_w_s;           // per camera frame
  std::vector<Eigen::Vector3d> v_w;  // per camera frame
};

// EuRoC's cam0 extrinsic (sensor.yaml T_BS inverted), rounded: a realistic T_cam_imu.
inline SE3d EurocCam0TCamImu() {
  Eigen::Matrix4d T_s_c;
  // clang-format off
  T_s_c << 0.0148655429818, -0.999880929698,  0.00414029679422, -0.0216401454975,
           0.999557249008,   0.0149672133247, 0.025715529948,   -0.064676986768,
          -0.0257744366974,  0.00375618835797, 0.999660727178,   0.00981073058949,
           0.0, 0.0, 0.0, 1.0;
  // clang-format on
  const SO3d R_s_c = SO3d::FromMatrix(T_s_c.topLeftCorner<3, 3>());
  return SE3d(R_s_c, T_s_c.topRightCorner<3, 1>()).inverse();
}

inline Scenario MakeScenario(const AnalyticTrajectory& trajectory, const ScenarioOptions& o) {
  Scenario s;
  s.scale = o.scale;
  s.gyro_bias = o.gyro_bias;
  s.T_cam_imu = o.T_cam_imu;
  const Eigen::Vector3d g_w(0.0, 0.0, -o.gravity);
  const double h = 1.0 / o.imu_rate_hz;
  const int64_t step_ns = static_cast<int64_t>(1e9 / o.imu_rate_hz + 0.5);
  const int num_samples = static_cast<int>(o.duration_s * o.imu_rate_hz + 0.5) + 1;

  // Clean readings (no bias) and the analytic states at every sample.
  std::vector<TrajectoryState> states(num_samples);
  std::vector<ImuSample> clean(num_samples);
  for (int k = 0; k < num_samples; ++k) {
    const double t_s = o.trajectory_start_s + k * step_ns * 1e-9;
    states[k] = trajectory.Evaluate(t_s);
    clean[k].t_ns = o.start_ns + k * step_ns;
    clean[k].gyro = states[k].w_s;
    clean[k].accel = states[k].T_w_s.so3().inverse() * (states[k].a_w - g_w);
  }

  // True poses and velocities at every sample.
  std::vector<SE3d> T_w_s(num_samples);
  std::vector<Eigen::Vector3d> v_w(num_samples);
  if (o.truth == Truth::kContinuous) {
    for (int k = 0; k < num_samples; ++k) {
      T_w_s[k] = states[k].T_w_s;
      v_w[k] = states[k].v_w;
    }
  } else {
    // Midpoint integration in the world frame (vio/preintegration.h's scheme):
    //   R' = R Exp((w_k + w_k+1)/2 h),  a = (R f_k + R' f_k+1)/2 + g_w,
    //   p' = p + v h + a h^2/2,  v' = v + a h.
    SO3d R = states[0].T_w_s.so3();
    Eigen::Vector3d p = states[0].T_w_s.translation();
    Eigen::Vector3d v = states[0].v_w;
    T_w_s[0] = SE3d(R, p);
    v_w[0] = v;
    for (int k = 0; k + 1 < num_samples; ++k) {
      const SO3d R1 = R * SO3d::Exp(0.5 * (clean[k].gyro + clean[k + 1].gyro) * h);
      const Eigen::Vector3d a = 0.5 * (R * clean[k].accel + R1 * clean[k + 1].accel) + g_w;
      p = p + v * h + 0.5 * h * h * a;
      v = v + h * a;
      R = SO3d::FromQuaternion(R1.quaternion());
      T_w_s[k + 1] = SE3d(R, p);
      v_w[k + 1] = v;
    }
  }

  // The readings the IMU reports: plus the gyro bias, plus noise if asked.
  s.imu = clean;
  if (o.imu_noise) {
    ImuNoise noise = o.noise;
    noise.update_rate_hz = o.imu_rate_hz;
    ImuNoiseGenerator generator(noise, o.gyro_bias, Eigen::Vector3d::Zero(), o.seed);
    for (ImuSample& sample : s.imu) generator.Corrupt(&sample, nullptr, nullptr);
  } else {
    for (ImuSample& sample : s.imu) sample.gyro += o.gyro_bias;
  }

  // Camera frames.
  std::mt19937 rng(static_cast<uint32_t>(o.seed) * 7919u + 1u);
  std::normal_distribution<double> normal(0.0, 1.0);
  const SE3d T_s_c = o.T_cam_imu.inverse();
  SE3d T_c0_w;
  for (int k = 0; k < num_samples; k += o.imu_samples_per_frame) {
    const SE3d T_w_c = T_w_s[k] * T_s_c;
    if (k == 0) {
      T_c0_w = T_w_c.inverse();
      s.R_w_c0 = T_w_c.so3();
      s.gravity_c0 = T_c0_w.so3() * g_w;
    }
    SE3d T_c0_c = T_c0_w * T_w_c;
    if (k > 0 && (o.camera_rotation_std_rad > 0.0 || o.camera_translation_std_m > 0.0)) {
      const Eigen::Vector3d dr(normal(rng), normal(rng), normal(rng));
      const Eigen::Vector3d dt(normal(rng), normal(rng), normal(rng));
      T_c0_c = SE3d(T_c0_c.so3() * SO3d::Exp(o.camera_rotation_std_rad * dr),
                    T_c0_c.translation() + o.camera_translation_std_m * dt);
    }
    StampedPose pose;
    pose.t_ns = s.imu[k].t_ns;
    pose.p = T_c0_c.translation() / o.scale;
    pose.q = T_c0_c.so3().quaternion();
    s.camera_poses.push_back(pose);
    s.T_w_s.push_back(T_w_s[k]);
    s.v_w.push_back(v_w[k]);
  }
  return s;
}

// A trajectory along a straight line at constant velocity without rotation (degenerate: the
// scale is unobservable).
inline AnalyticTrajectory ConstantVelocityTrajectory() {
  std::array<SinusoidChannel, 3> position;
  position[0].offset = 1.0;
  position[0].rate = 0.8;
  position[1].offset = -2.0;
  position[1].rate = 0.3;
  position[2].offset = 1.5;
  position[2].rate = 0.1;
  std::array<SinusoidChannel, 3> rpy;
  rpy[0].offset = 0.1;
  rpy[1].offset = -0.2;
  rpy[2].offset = 0.7;
  return AnalyticTrajectory("constant_velocity", position, rpy);
}

// Rich translation, but the body rotates about the world z axis only (yaw): the camera-IMU
// rotation about that axis is unobservable by hand-eye.
inline AnalyticTrajectory YawOnlyTrajectory() {
  std::array<SinusoidChannel, 3> position;
  position[0].terms = {{2.0, 0.6, 0.0}, {0.3, 1.7, 0.4}};
  position[1].terms = {{1.5, 0.9, 1.0}, {0.2, 2.1, 0.2}};
  position[2].offset = 1.5;
  position[2].terms = {{0.4, 1.3, 0.3}};
  std::array<SinusoidChannel, 3> rpy;
  rpy[2].terms = {{1.0, 0.7, 0.0}, {0.3, 1.9, 0.5}};
  return AnalyticTrajectory("yaw_only", position, rpy);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_ALIGN_TEST_DATA_H_
