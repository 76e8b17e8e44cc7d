// The warnings `splinecal calibrate` gives about its standard deviations (private to src/calib/):
// the data scattering more than the noise model explains, and each camera's poorly determined
// parameters, in plain words with their sizes.
#ifndef SPLINECAL_SRC_CALIB_CALIBRATION_WARNINGS_H_
#define SPLINECAL_SRC_CALIB_CALIBRATION_WARNINGS_H_

#include "splinecal/calib/calibrate.h"
#include "splinecal/estimation/imu_noise_estimate.h"

namespace splinecal {
namespace internal {

// Appends to result->warnings, from the stds, estimates, std_inflation and robust_clusters that
// `result` already holds (the cameras' calibration: the estimates).
void AddStandardDeviationWarnings(const CalibrateOptions& options,
                                  const ImuNoiseEstimate& noise,
                                  CalibrationResult* result);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_CALIBRATION_WARNINGS_H_
