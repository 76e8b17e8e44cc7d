// The motion `splinecal simulate` drives its IMU (and cameras) with, turned into spline control
// poses (docs/simulate.md): a recorded trajectory (TUM or EuRoC poses, fitted with
// estimation/pose_fit.h, its timestamps kept), the calibration motion over a target
// (sim/simulate_camera.h) or an analytic trajectory by name (sim/trajectories.h). Every kind is
// fitted with the knot layout KnotLayoutCovering(start_ns, end_ns, knot_spacing_ns), so the
// simulated range [start_ns, end_ns] lies inside the spline's valid range.
#ifndef SPLINECAL_SIM_SIMULATION_TRAJECTORY_H_
#define SPLINECAL_SIM_SIMULATION_TRAJECTORY_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/estimation/pose_fit.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

struct SimulationTrajectory {
  // A recorded trajectory T_w_s at its own timestamps; when not empty it is the one simulated.
  std::vector<StampedPose> recorded_poses;
  std::string recorded_source;  // how the outputs name it (the file's path)
  // Otherwise "vio_course", "figure8", "random" or "calibration".
  std::string name = "vio_course";
  uint64_t seed = 0;  // the shape of "random" and "calibration"
  // "calibration" only: the target's centre the cameras look at, and cam0's T_cam_imu (the motion
  // is laid out for cam0).
  Eigen::Vector3d target_centre_w = Eigen::Vector3d::Zero();
  SE3d T_cam_imu;
};

struct SimulationSpline {
  std::string source;  // the trajectory's name, or recorded_source
  PoseFitResult fit;   // the control poses and the fit's residuals to the trajectory
};

// Fits the control poses of `trajectory` over [start_ns, end_ns]. options.progress (if set) gets
// a line before the fit, the solver's lines (recorded and analytic trajectories) and the fit's
// RMS. Throws splinecal::Error for an unknown name, knot_spacing_ns <= 0 or end_ns < start_ns,
// and as FitControlPoses for a recorded trajectory that does not cover the range.
SimulationSpline FitSimulationTrajectory(const SimulationTrajectory& trajectory,
                                         int64_t start_ns,
                                         int64_t end_ns,
                                         int64_t knot_spacing_ns,
                                         const PoseFitOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_SIM_SIMULATION_TRAJECTORY_H_
