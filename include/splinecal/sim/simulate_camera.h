// Camera simulation for `splinecal simulate --camchain ...`: observations.csv of a calibration
// target and/or natural landmarks seen by the cameras of a camchain riding on the IMU spline
// T_w_s(t), with the rolling-shutter exposure time solved per point (camera/rolling_shutter.h).
//
// Frames. Camera n takes frames at t_cam_k = t_first + k / camera_rate (camera clock, t_first the
// first stamp whose whole readout [t_cam + time_offset, t_cam + time_offset + (height - 1)
// line_delay] lies in [start_ns, end_ns] in the IMU clock, docs/conventions.md "Time"). Every stamp
// is rounded to the nanosecond once, never accumulated.
//
// A point is observed in a frame when (visibility and field-of-view checks):
//   * its exposure time solves (Newton, camera/rolling_shutter.h; the row falls in the image),
//   * its distance from the camera centre is in [min_depth_m, max_depth_m],
//   * it is in the camera model's valid region and the projection has not folded back there
//     (Camera::IsDistortionMonotonic; a wide-angle camera sees points behind its image plane),
//     and the pixel (before noise) is inside the image,
//   * for a planar target: the camera is on the target's +z side and views it at most
//     max_view_angle_deg away from the target's normal (detectors lose tags seen edge-on).
// Pixel noise: N(0, pixel_noise_px^2) per coordinate from the library's seeded Gaussian sampler
// (sim/noise_generator.h): the same seed gives the same file.
//
// Natural landmarks: num_landmarks points, each placed by picking a random frame, a random pixel
// (of camera 0, one that has a bearing) and a random distance in [landmark_min_depth_m,
// landmark_max_depth_m] along its bearing (Camera::UnprojectToBearing), so every landmark is
// seen at least from where it was made; ids start at kLandmarkIdBase.
//
// A trajectory for calibration sequences: CalibrationCameraPose(t) moves the camera over the
// target's centre (height ~1 m), always looking near it, with rotation about all three axes and
// accelerations of a few m/s^2 ("lively"); FitCalibrationTrajectory turns it into the IMU
// spline T_w_s = T_w_c T_cam_imu by estimation/pose_fit.h.
#ifndef SPLINECAL_SIM_SIMULATE_CAMERA_H_
#define SPLINECAL_SIM_SIMULATE_CAMERA_H_

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/camera/target.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/lie/se3.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {

// Landmark point ids start here (target corner ids stay below it).
inline constexpr int64_t kLandmarkIdBase = 1000000;

struct CameraSimulationOptions {
  double camera_rate_hz = 20.0;  // frames per second, every camera
  double pixel_noise_px = 0.5;   // std per pixel coordinate [px]; 0 = noise-free
  uint64_t seed = 1;

  // The calibration target and its pose in the world (has_target = false: none).
  bool has_target = false;
  CalibrationTarget target;
  SE3d T_w_t;
  double max_view_angle_deg = 75.0;

  // Natural landmarks.
  int num_landmarks = 0;
  double landmark_min_depth_m = 1.0;
  double landmark_max_depth_m = 6.0;

  double min_depth_m = 0.05;  // closer points (distance from the camera) are not observed [m]
  double max_depth_m = 50.0;  // farther points are not observed [m]
};

struct CameraSimulationResult {
  std::vector<Observation> observations;           // sorted (t_ns, cam_id, point_id)
  std::map<int64_t, Eigen::Vector3d> landmarks_w;  // id -> position in the world [m]
  int num_frames = 0;                              // frames taken (all cameras)
  int num_frames_with_target = 0;                  // frames with at least one target corner
  int num_target_observations = 0;
  int num_landmark_observations = 0;
};

// Simulates every camera of `camchain` over [start_ns, end_ns] (IMU clock). The spline is T_w_s
// in the IMU clock. Throws splinecal::Error for a non-positive rate, a negative noise, an empty
// camchain, a range outside the spline, or a range too short for one frame.
CameraSimulationResult SimulateCameras(const SE3Splined& spline,
                                       const Camchain& camchain,
                                       int64_t start_ns,
                                       int64_t end_ns,
                                       const CameraSimulationOptions& options);

// Writes the camera truth for result.yaml: per camera T_cam_imu, the time offset (under Kalibr's
// key timeshift_cam_imu), line_delay,
// and the target pose T_w_t, the counts of frames and observations, the landmark count.
void WriteCameraSimulationTruth(const Camchain& camchain,
                                const CameraSimulationOptions& options,
                                const CameraSimulationResult& result,
                                YamlWriter* yaml);

// The camera pose T_w_c at t_s seconds of a calibration sequence over a target whose centre is
// at target_centre_w (target plane z = target_centre_w.z, seen from above). `seed` varies the
// phases and periods (seed 0 is the documented default shape).
SE3d CalibrationCameraPose(double t_s, const Eigen::Vector3d& target_centre_w, uint64_t seed = 0);

// The IMU spline of that camera motion over [start_ns, end_ns]: T_w_s = T_w_c T_cam_imu sampled
// every knot_spacing / 10 and fitted with the knot layout KnotLayoutCovering(start_ns, end_ns,
// knot_spacing_ns) (the same layout `splinecal calibrate` uses for that IMU range).
PoseFitResult FitCalibrationTrajectory(const Eigen::Vector3d& target_centre_w,
                                       const SE3d& T_cam_imu,
                                       int64_t start_ns,
                                       int64_t end_ns,
                                       int64_t knot_spacing_ns,
                                       uint64_t seed = 0);

// A whole simulated calibration sequence (tests, benchmark, demo): the calibration trajectory
// over the target (or over the origin without one), the IMU (sim/simulate_imu.h) and the cameras.
struct CalibrationSequenceOptions {
  int64_t start_ns = 1'000'000'000;
  double duration_s = 60.0;
  double knot_spacing_s = 0.05;    // of the truth spline (use the same in `calibrate`)
  uint64_t trajectory_seed = 0;    // CalibrationCameraPose's shape
  SimulationOptions imu;           // rate, noise, biases, seed
  CameraSimulationOptions camera;  // rate, pixel noise, target, landmarks, seed
};

struct CalibrationSequence {
  SE3Splined spline = SE3Splined(std::vector<SE3d>(4), 0, 1);  // T_w_s, IMU clock
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> ground_truth;
  CameraSimulationResult cameras;
};

// The trajectory is laid out for camchain[0]'s T_cam_imu. Throws splinecal::Error for bad
// options (as SimulateImu and SimulateCameras).
CalibrationSequence SimulateCalibrationSequence(const Camchain& camchain,
                                                const CalibrationSequenceOptions& options);

// The centre of a planar target's points in the world (T_w_t times the mean of the points).
Eigen::Vector3d TargetCentre(const CalibrationTarget& target, const SE3d& T_w_t);

}  // namespace splinecal

#endif  // SPLINECAL_SIM_SIMULATE_CAMERA_H_
