// A simulated camera-IMU calibration sequence for the calibrate tests and benchmark: the lively
// target-viewing trajectory of sim/simulate_camera.h, a 200 Hz IMU with the ADIS16448 noise
// (EuRoC), a 20 Hz EuRoC-like camera (752 x 480, radtan; ScenarioOptions::camera replaces it)
// with 0.5 px noise, an aprilgrid of
// 6 x 6 tags of 8.8 cm (144 corners, ~100 visible per frame).
//
// By default the data come from a spline fitted on the knot layout `calibrate` uses (its model is
// then exact); ScenarioOptions::closed_form makes them from ClosedFormCalibrationTrajectory
// itself (calib/closed_form_simulation.h), which no spline represents exactly, as on real data.
#ifndef SPLINECAL_TESTS_CALIB_CALIBRATE_TEST_SCENARIO_H_
#define SPLINECAL_TESTS_CALIB_CALIBRATE_TEST_SCENARIO_H_

#include <array>
#include <cstdint>
#include <optional>
#include <random>
#include <vector>

#include "calib/camera_test_scene.h"
#include "calib/closed_form_simulation.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

struct CalibrationScenario {
  Camchain truth;  // the rig that made the data
  Camchain start;  // what the calibration is given (perturbed extrinsic, no offset/delay)
  CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  // The truth T_w_s: the spline (default), or the closed form (closed_form; the spline is then
  // a placeholder), trajectory time (t_ns - start_ns) * 1e-9 s.
  SE3Splined spline = SE3Splined(std::vector<SE3d>(4), 0, 1);
  std::optional<AnalyticTrajectory> trajectory;
  int64_t start_ns = 0;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d(0.002, -0.001, 0.0015);
  Eigen::Vector3d accel_bias = Eigen::Vector3d(0.05, -0.03, 0.02);
  std::vector<ImuSample> imu;
  std::vector<Observation> observations;
  CameraSimulationResult camera_result;
};

struct ScenarioOptions {
  double duration_s = 20.0;
  double line_delay_s = 3e-5;  // 0 = global shutter
  double time_offset_s = 0.0042;
  double pixel_noise_px = 0.5;
  bool imu_noise = true;
  int num_landmarks = 0;
  bool target = true;
  double knot_spacing_s = 0.05;
  uint64_t seed = 1;
  // Data from ClosedFormCalibrationTrajectory(seed) instead of a spline (target only, no
  // landmarks).
  bool closed_form = false;
  // closed_form only: adds to roll, pitch and yaw a term of this amplitude [rad] of period
  // ~0.5 s (a rig shaken by hand: the angular accelerations the IMU size effect shows in).
  double shake_amplitude_rad = 0.0;
  // The rig's camera (intrinsics, image size); none: EuRoC's cam0 (pinhole-radtan).
  std::optional<Camera> camera;
};

// A closed-form IMU trajectory T_w_s over a target whose centre is target_centre_w (the camera
// ~1 m above it, looking down: roll ~ pi turns the IMU's z, and with it the camera's optical
// axis, to -z_w). Sums of sinusoids of periods 0.8-5 s: body rates of 1-2 rad/s about every
// axis and accelerations of 1-3 m/s^2 at their peaks (bounds from the amplitudes), the tilt
// partly following the position so that the target stays in view (8 s of it: ~142 of the 144
// corners per frame). `seed` scales every period by [0.85, 1.15] and draws the phases. A
// shake_amplitude_rad > 0 adds one term of periods 0.45, 0.5, 0.55 s to roll, pitch and yaw
// (drawn after the others: the rest of the trajectory stays the same).
inline AnalyticTrajectory ClosedFormCalibrationTrajectory(uint64_t seed,
                                                          const Eigen::Vector3d& target_centre_w,
                                                          double shake_amplitude_rad = 0.0) {
  std::mt19937_64 engine(seed);
  auto uniform = [&engine]() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
  auto term = [&](double amplitude, double period_s) {
    const double scale = 0.85 + 0.3 * uniform();
    return SinusoidChannel::Term{amplitude, 2.0 * kPi / (period_s * scale), 2.0 * kPi * uniform()};
  };
  std::array<SinusoidChannel, 3> p;
  std::array<SinusoidChannel, 3> rpy;
  // Position: a slow sweep and a faster wiggle per axis.
  const SinusoidChannel::Term x_sweep = term(0.20, 4.3);
  const SinusoidChannel::Term y_sweep = term(0.15, 3.7);
  p[0] = {target_centre_w.x(), 0.0, {x_sweep, term(0.05, 1.3)}};
  p[1] = {target_centre_w.y(), 0.0, {y_sweep, term(0.04, 1.1)}};
  p[2] = {target_centre_w.z() + 1.0, 0.0, {term(0.12, 3.1)}};
  // Attitude: the tilt turns the view back towards the centre (pitch with x, roll with -y; with
  // roll ~ pi the optical axis is ~(-pitch, roll - pi, -1)), plus independent terms.
  SinusoidChannel::Term pitch_follow = x_sweep;
  pitch_follow.amplitude = 0.7 * x_sweep.amplitude;
  SinusoidChannel::Term roll_follow = y_sweep;
  roll_follow.amplitude = -0.7 * y_sweep.amplitude;
  rpy[0] = {kPi, 0.0, {roll_follow, term(0.15, 2.3), term(0.06, 0.9)}};
  rpy[1] = {0.0, 0.0, {pitch_follow, term(0.15, 2.9), term(0.06, 1.0)}};
  rpy[2] = {0.3, 0.0, {term(0.45, 3.3), term(0.1, 1.2)}};
  if (shake_amplitude_rad > 0.0) {
    rpy[0].terms.push_back(term(shake_amplitude_rad, 0.45));
    rpy[1].terms.push_back(term(shake_amplitude_rad, 0.5));
    rpy[2].terms.push_back(term(shake_amplitude_rad, 0.55));
  }
  return AnalyticTrajectory("closed_form_calibration", p, rpy);
}

inline CalibrationScenario MakeCalibrationScenario(const ScenarioOptions& o) {
  CalibrationScenario s;
  CameraCalibration cam;
  cam.camera = o.camera ? *o.camera : EurocCamera();
  cam.T_cam_imu =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.02, -0.01, 1.55)), Eigen::Vector3d(0.06, -0.02, 0.01));
  cam.time_offset_s = o.time_offset_s;
  cam.line_delay_s = o.line_delay_s;
  s.truth = {cam};
  CameraCalibration given = cam;
  // 3 degrees and 3 cm off, no time offset, global shutter.
  given.T_cam_imu =
      cam.T_cam_imu * SE3d::Exp((Vector6d() << 0.02, -0.015, 0.01, 0.03, -0.035, 0.02).finished());
  given.time_offset_s = 0.0;
  given.line_delay_s = 0.0;
  s.start = {given};
  CalibrationSequenceOptions options;
  options.duration_s = o.duration_s;
  options.knot_spacing_s = o.knot_spacing_s;
  options.trajectory_seed = o.seed - 1;
  options.imu.noise = ImuNoise::Adis16448();
  options.imu.noise_free = !o.imu_noise;
  options.imu.gyro_bias = s.gyro_bias;
  options.imu.accel_bias = s.accel_bias;
  options.imu.seed = o.seed;
  options.camera.pixel_noise_px = o.pixel_noise_px;
  options.camera.seed = o.seed + 100;
  options.camera.has_target = o.target;
  options.camera.target = s.target;
  options.camera.num_landmarks = o.num_landmarks;
  s.start_ns = options.start_ns;
  if (o.closed_form) {
    const int64_t end_ns = options.start_ns + std::llround(o.duration_s * 1e9);
    s.trajectory = ClosedFormCalibrationTrajectory(
        o.seed, TargetCentre(options.camera.target, options.camera.T_w_t), o.shake_amplitude_rad);
    s.imu = SimulateImuFromTrajectory(*s.trajectory, options.start_ns, end_ns, options.imu);
    s.camera_result =
        SimulateTargetFromTrajectory(*s.trajectory, options.start_ns, end_ns, cam, options.camera);
    s.observations = s.camera_result.observations;
    return s;
  }
  const CalibrationSequence sequence = SimulateCalibrationSequence(s.truth, options);
  s.spline = sequence.spline;
  s.imu = sequence.imu;
  s.camera_result = sequence.cameras;
  s.observations = s.camera_result.observations;
  return s;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_CALIBRATE_TEST_SCENARIO_H_
