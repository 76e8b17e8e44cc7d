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
  run->more_imu.resize(run->more_imus.size());
  for (size_t k = 0; k < run->more_imus.size(); ++k) {
    SimulationOptions options = run->options;
    options.imu = run->more_imus[k];
    options.seed = run->options.seed + 200 + k;
    SimulateImu(spline, run->start_ns, run->end_ns, options, &run->more_imu[k], nullptr);
  }
  if (!run->camchain.empty()) {
    run->cameras =
        SimulateCameras(spline, run->camchain, run->start_ns, run->end_ns, run->camera_options);
  }
}

}  // namespace splinecal
