// One run of `splinecal simulate` (docs/simulate.md): its settings and what it produced, and the
// pipeline that produces it. Its files are written by report/simulate_report.h and
// report/command_outputs.h.
#ifndef SPLINECAL_SIM_SIMULATION_RESULT_H_
#define SPLINECAL_SIM_SIMULATION_RESULT_H_

#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/euroc.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/simulation_trajectory.h"

namespace splinecal {

// One simulation run: its spline, its settings and what it produced.
struct SimulationRun {
  SimulationSpline spline;
  int64_t start_ns = 0;  // the simulated range, IMU clock
  int64_t end_ns = 0;
  double knot_spacing_s = 0.0;  // as requested (spline.fit.layout has it in ns)
  SimulationOptions options;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;  // not empty
  // Further IMUs rigidly mounted on the body (imu1, imu2, ...; options.imu is imu0, the
  // reference), each simulated with options but its own model, pose, clock offset and noise seed
  // (options.seed + 200 + k for more_imus[k]); more_imu[k] are its readings.
  std::vector<ImuCalibration> more_imus;
  std::vector<std::vector<ImuSample>> more_imu;
  Camchain camchain;                    // empty: no cameras
  CameraSimulationOptions camera_options;
  CameraSimulationResult cameras;
};

// Runs the simulation `run` describes (start_ns, end_ns, knot_spacing_s, options, camchain and
// camera_options set by the caller): fits the spline to `trajectory` (progress through
// fit_options), simulates the IMU on it and, with a camchain, the cameras; fills run->spline,
// imu, truth and cameras. The one pipeline of `splinecal simulate` and the Python module.
void RunSimulation(const SimulationTrajectory& trajectory,
                   const PoseFitOptions& fit_options,
                   SimulationRun* run);

}  // namespace splinecal

#endif  // SPLINECAL_SIM_SIMULATION_RESULT_H_
