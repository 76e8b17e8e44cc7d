#include <cmath>

#include "splinecal/sim/simulation_result.h"

namespace splinecal {

void RunSimulation(const SimulationTrajectory& trajectory,
                   const PoseFitOptions& fit_options,
                   SimulationRun* run) {
  const int64_t knot_spacing_ns = static_cast<int64_t>(std::llround(run->knot_spacing_s * 1e9));
  run->spline =
      FitSimulationTrajectory(trajectory, run->start_ns, run->end_ns, knot_spacing_ns, fit_options);
  const SE3Splined spline = run->spline.fit.MakeSpline();
  SimulateImu(spline, run->start_ns, run->end_ns, run->options, &run->imu, &run->truth);
  if (!run->camchain.empty()) {
    run->cameras =
        SimulateCameras(spline, run->camchain, run->start_ns, run->end_ns, run->camera_options);
  }
}

}  // namespace splinecal
