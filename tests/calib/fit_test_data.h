// Simulated data for the `splinecal fit` tests (fit_test.cc, fit_slow_test.cc): a true spline
// from an analytic trajectory, IMU readings predicted from it (sim/simulate_imu.h), and poses of
// the pose source sampled from it with an optional time offset, extrinsic, world tilt and noise.
// With FitScenario::closed_form the IMU and the poses come from the analytic trajectory itself
// (calib/closed_form_simulation.h): no spline on the fit's knots is then exactly right.
#ifndef SPLINECAL_TESTS_CALIB_FIT_TEST_DATA_H_
#define SPLINECAL_TESTS_CALIB_FIT_TEST_DATA_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <random>
#include <string>
#include <vector>

#include "calib/closed_form_simulation.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

struct FitScenario {
  std::string trajectory = "random";
  uint64_t trajectory_seed = 3;
  RandomTrajectoryOptions random_trajectory;  // the shape of "random"
  // IMU and poses from the analytic trajectory, not from a spline fitted to it (FitData::truth
  // is then a placeholder).
  bool closed_form = false;
  double duration_s = 20.0;
  int64_t knot_spacing_ns = 100'000'000;
  // The truth spline's model (spline/trajectory_model.h): the IMU and the poses come from it.
  TrajectoryModel truth_model = TrajectoryModel::kSE3;
  double pose_rate_hz = 10.0;
  // IMU: noise densities (random walks 0 unless set), constant biases.
  bool imu_noise = false;
  ImuNoise noise = [] {
    ImuNoise n = ImuNoise::Adis16448();
    n.gyroscope_random_walk = 0.0;
    n.accelerometer_random_walk = 0.0;
    return n;
  }();
  Eigen::Vector3d gyro_bias = Eigen::Vector3d(0.012, -0.021, 0.006);
  Eigen::Vector3d accel_bias = Eigen::Vector3d(0.05, 0.11, -0.08);
  uint64_t noise_seed = 5;
  // Pose source: noise, time offset (t_imu = t_pose + offset), extrinsic T_m_s, and the rotation
  // of its world relative to the simulator's gravity-aligned one (gravity then points along
  // R_world (0, 0, -g)).
  bool pose_noise = false;
  double pose_sigma_m = 1e-3;
  double pose_sigma_rad = 1e-3;
  double time_offset_s = 0.0;
  SE3d T_m_s;
  SO3d R_world;
};

struct FitData {
  SE3Splined truth = SE3Splined(std::vector<SE3d>(4), 0, 1);  // T_w_s in the pose world
  std::vector<ImuSample> imu;
  std::vector<StampedPose> poses;
  Eigen::Vector3d gravity_w = Eigen::Vector3d::Zero();
};

// The named trajectories of sim/trajectories.h, plus "translation_only": sinusoidal motion with a
// constant attitude (no rotation at all).
inline AnalyticTrajectory ScenarioTrajectory(const FitScenario& scenario) {
  if (scenario.trajectory == "random") {
    return RandomTrajectory(scenario.trajectory_seed, scenario.random_trajectory);
  }
  if (scenario.trajectory != "translation_only") {
    return MakeTrajectory(scenario.trajectory, scenario.trajectory_seed);
  }
  std::array<SinusoidChannel, 3> position;
  const double periods[3] = {7.0, 5.0, 11.0};
  for (int a = 0; a < 3; ++a) {
    position[a].offset = 1.0;
    position[a].terms.push_back({1.5, 2.0 * kPi / periods[a], 0.3 * a});
  }
  std::array<SinusoidChannel, 3> attitude;
  attitude[0].offset = 0.1;
  attitude[1].offset = -0.2;
  attitude[2].offset = 0.7;
  return AnalyticTrajectory("translation_only", position, attitude);
}

// The IMU's noise, biases and seed.
inline SimulationOptions ImuSimulationOptions(const FitScenario& scenario) {
  SimulationOptions simulation;
  simulation.noise = scenario.noise;
  simulation.noise_free = !scenario.imu_noise;
  simulation.gyro_bias = scenario.gyro_bias;
  simulation.accel_bias = scenario.accel_bias;
  simulation.seed = scenario.noise_seed;
  return simulation;
}

inline FitData MakeFitData(const FitScenario& scenario) {
  constexpr int64_t kStartNs = 1'403'715'273'262'142'976;  // an EuRoC-like epoch
  const int64_t end_ns = kStartNs + std::llround(scenario.duration_s * 1e9);
  if (scenario.closed_form) {
    FitData data;
    const SimulationOptions simulation = ImuSimulationOptions(scenario);
    const AnalyticTrajectory trajectory = ScenarioTrajectory(scenario);
    data.imu = SimulateImuFromTrajectory(trajectory, kStartNs, end_ns, simulation);
    data.gravity_w = scenario.R_world * Eigen::Vector3d(0.0, 0.0, -kDefaultGravity);
    PoseSourceOptions source;
    source.step_ns = std::llround(1e9 / scenario.pose_rate_hz);
    source.time_offset_s = scenario.time_offset_s;
    source.T_m_s = scenario.T_m_s;
    source.R_world = scenario.R_world;
    source.sigma_m = scenario.pose_noise ? scenario.pose_sigma_m : 0.0;
    source.sigma_rad = scenario.pose_noise ? scenario.pose_sigma_rad : 0.0;
    source.seed = scenario.noise_seed + 1000;
    data.poses = SamplePoseSource(trajectory, kStartNs, end_ns, source);
    return data;
  }
  PoseFitOptions truth_fit;
  truth_fit.trajectory = scenario.truth_model;
  const SE3Splined spline = FitAnalyticTrajectory(ScenarioTrajectory(scenario),
                                                  kStartNs,
                                                  end_ns,
                                                  scenario.knot_spacing_ns,
                                                  /*pose_step_ns=*/0,
                                                  truth_fit)
                                .MakeSpline();
  FitData data;
  const SimulationOptions simulation = ImuSimulationOptions(scenario);
  SimulateImu(spline, spline.start_time_ns(), spline.end_time_ns(), simulation, &data.imu, nullptr);

  // The truth in the pose source's world.
  const SE3d T_world(scenario.R_world, Eigen::Vector3d::Zero());
  std::vector<SE3d> control = spline.control_poses();
  for (SE3d& T : control) T = T_world * T;
  data.truth = SE3Splined(control, spline.t0_ns(), spline.dt_ns(), spline.model());
  data.gravity_w = scenario.R_world * Eigen::Vector3d(0.0, 0.0, -kDefaultGravity);

  std::mt19937_64 rng(scenario.noise_seed + 1000);
  std::normal_distribution<double> normal(0.0, 1.0);
  const int64_t step_ns = std::llround(1e9 / scenario.pose_rate_hz);
  const int64_t offset_ns = std::llround(scenario.time_offset_s * 1e9);
  const SE3d T_s_m = scenario.T_m_s.inverse();
  for (int64_t t = data.truth.start_time_ns(); t <= data.truth.end_time_ns(); t += step_ns) {
    SE3d T_w_m = data.truth.PoseNs(t) * T_s_m;
    if (scenario.pose_noise) {
      Eigen::Vector3d dp;
      Eigen::Vector3d dphi;
      for (int a = 0; a < 3; ++a) dp[a] = scenario.pose_sigma_m * normal(rng);
      for (int a = 0; a < 3; ++a) dphi[a] = scenario.pose_sigma_rad * normal(rng);
      T_w_m = SE3d(T_w_m.so3() * SO3d::Exp(dphi), T_w_m.translation() + dp);
    }
    StampedPose pose;
    pose.t_ns = t - offset_ns;
    pose.p = T_w_m.translation();
    pose.q = T_w_m.so3().quaternion();
    data.poses.push_back(pose);
  }
  return data;
}

// Control poses perturbed by Exp(d), d ~ N(0, sigma_m^2) translation, N(0, sigma_rad^2) rotation.
inline std::vector<SE3d> PerturbedControlPoses(const SE3Splined& spline,
                                               double sigma_m,
                                               double sigma_rad,
                                               uint64_t seed) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<SE3d> poses = spline.control_poses();
  for (SE3d& T : poses) {
    Vector6d d;
    for (int k = 0; k < 3; ++k) d[k] = sigma_m * normal(rng);
    for (int k = 3; k < 6; ++k) d[k] = sigma_rad * normal(rng);
    T = T * SE3d::Exp(d);
  }
  return poses;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_FIT_TEST_DATA_H_
