// The gates where observations meet a target and cameras: a wrong target layout
// (camera/target_layout_check.h) and corners outside the images (camera/image_bounds_check.h).
// Both lead to a calibration that converges to a confident wrong answer, so they refuse the
// input (splinecal::Error, one line) before anything is solved or written. CalibrateIntrinsics and
// Calibrate call them first (so the Python module, which calls those, gets the same checks);
// the commands call them earlier with the file names, while reading their inputs.
#ifndef SPLINECAL_CAMERA_OBSERVATION_GATES_H_
#define SPLINECAL_CAMERA_OBSERVATION_GATES_H_

#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"

namespace splinecal {

// What the messages call the inputs (a command passes its file names and flags).
struct ObservationSources {
  std::string observations = "observations";
  std::string target = "the target";
  std::string image_size = "the camera model";  // e.g. "--resolution", "camchain.yaml"
};

// target may be null (no target: only the image bounds are checked).
void CheckObservationInputs(const std::vector<Observation>& observations,
                            const CalibrationTarget* target,
                            const std::vector<Camera>& cameras,
                            const ObservationSources& sources = {});
void CheckObservationInputs(const std::vector<Observation>& observations,
                            const CalibrationTarget* target,
                            const Camchain& camchain,
                            const ObservationSources& sources = {});

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_OBSERVATION_GATES_H_
