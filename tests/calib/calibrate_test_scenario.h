// A simulated camera-IMU calibration sequence for the calibrate tests and benchmark: the lively
// target-viewing trajectory of sim/simulate_camera.h, a 200 Hz IMU with the ADIS16448 noise
// (EuRoC), a 20 Hz EuRoC-like camera (752 x 480, radtan) with 0.5 px noise, an aprilgrid of
// 6 x 6 tags of 8.8 cm (144 corners, ~100 visible per frame).
#ifndef SPLINECAL_TESTS_CALIB_CALIBRATE_TEST_SCENARIO_H_
#define SPLINECAL_TESTS_CALIB_CALIBRATE_TEST_SCENARIO_H_

#include <cstdint>
#include <vector>

#include "calib/camera_test_scene.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"

namespace splinecal {
namespace testing {

struct CalibrationScenario {
  Camchain truth;  // the rig that made the data
  Camchain start;  // what the calibration is given (perturbed extrinsic, no offset/delay)
  CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  SE3Splined spline = SE3Splined(std::vector<SE3d>(4), 0, 1);
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
};

inline CalibrationScenario MakeCalibrationScenario(const ScenarioOptions& o) {
  CalibrationScenario s;
  CameraCalibration cam;
  cam.camera = EurocCamera();
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
