// result.yaml of `splinecal simulate` (docs/simulate.md, "Outputs"): what was simulated (the
// trajectory, time range, rate, seed, gravity, noise densities, initial and final biases), how
// well the spline fits the trajectory, and with cameras their truth (sim/simulate_camera.h,
// WriteCameraSimulationTruth). report/command_outputs.h lists it with the run's other files.
#ifndef SPLINECAL_REPORT_SIMULATE_REPORT_H_
#define SPLINECAL_REPORT_SIMULATE_REPORT_H_

#include <string>

#include "splinecal/sim/simulation_result.h"

namespace splinecal {

std::string SimulationResultYaml(const SimulationRun& run);

// Whether the run has a model other than `calibrated` or several IMUs: then it writes their
// truth, Kalibr's imu-*.yaml layout (io/imu_models_yaml.h), as imu_models.yaml.
bool HasImuModels(const SimulationRun& run);
std::string SimulationImuModelsYaml(const SimulationRun& run);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_SIMULATE_REPORT_H_
