#include "splinecal/camera/observation_gates.h"

#include "splinecal/camera/image_bounds_check.h"
#include "splinecal/camera/target_layout_check.h"

namespace splinecal {

void CheckObservationInputs(const std::vector<Observation>& observations,
                            const CalibrationTarget* target,
                            const std::vector<Camera>& cameras,
                            const ObservationSources& sources) {
  // The image size first: its message is the more specific one (a wrong size does not disturb
  // the layout check, which uses the pixels only relative to each other).
  CheckCornersInsideImages(observations, cameras, sources.observations, sources.image_size);
  if (target != nullptr) {
    CheckTargetLayout(observations, *target, sources.observations, sources.target);
  }
}

void CheckObservationInputs(const std::vector<Observation>& observations,
                            const CalibrationTarget* target,
                            const Camchain& camchain,
                            const ObservationSources& sources) {
  std::vector<Camera> cameras;
  cameras.reserve(camchain.size());
  for (const CameraCalibration& calibration : camchain) cameras.push_back(calibration.camera);
  CheckObservationInputs(observations, target, cameras, sources);
}

}  // namespace splinecal
