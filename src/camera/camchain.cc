#include "splinecal/camera/camchain.h"

#include "splinecal/error.h"

namespace splinecal {

const Observation* FindObservationWithoutCamera(const std::vector<Observation>& observations,
                                                const Camchain& camchain) {
  for (const Observation& o : observations) {
    if (o.cam_id < 0 || o.cam_id >= static_cast<int>(camchain.size())) return &o;
  }
  return nullptr;
}

void CheckCameraIds(const std::vector<Observation>& observations,
                    const Camchain& camchain,
                    const std::string& observations_path,
                    const std::string& camchain_path) {
  const Observation* o = FindObservationWithoutCamera(observations, camchain);
  if (o == nullptr) return;
  throw Error(observations_path,
              0,
              "cam_id " + std::to_string(o->cam_id) + " (frame t_ns " + std::to_string(o->t_ns) +
                  ") has no camera in " + camchain_path + ", which describes " +
                  std::to_string(camchain.size()) + " camera(s): wrong camchain or cam_id column");
}

}  // namespace splinecal
