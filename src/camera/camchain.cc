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

std::vector<int> KalibrIntrinsicsOrder(const Camera& camera) {
  switch (camera.projection) {
    case ProjectionModel::kOmni:
      return {4, 0, 1, 2, 3};
    case ProjectionModel::kEucm:
    case ProjectionModel::kDoubleSphere:
      return {4, 5, 0, 1, 2, 3};
    default:
      return {0, 1, 2, 3};
  }
}

std::vector<int> KalibrDistortionOrder(const Camera& camera) {
  std::vector<int> order;
  int count = 0;
  switch (camera.distortion) {
    case DistortionModel::kNone:
      count = 0;
      break;
    case DistortionModel::kRadTan:
      // OpenCV's k3 when it is estimated or not 0.
      count = camera.radtan_k3 || camera.distortion_coeffs(4) != 0.0 ? 5 : 4;
      break;
    case DistortionModel::kEquidistant:
      count = 4;
      break;
    case DistortionModel::kFov:
      count = 1;
      break;
  }
  for (int i = 0; i < count; ++i) order.push_back(kDistortionCoeffsIndex + i);
  return order;
}

}  // namespace splinecal
