#include "camera_selection.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "splinecal/error.h"

namespace splinecal {
namespace cli {

std::vector<int> ParseCameraSelection(const std::string& text, int num_cameras) {
  std::vector<int> selection;
  if (text.empty()) {
    for (int c = 0; c < num_cameras; ++c) selection.push_back(c);
    return selection;
  }
  std::stringstream stream(text);
  std::string item;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    const long id = std::strtol(item.c_str(), &end, 10);
    if (item.empty() || *end != '\0' || id < 0 || id >= num_cameras) {
      throw Error("--cameras: '" + item + "' is not a camera index of the camchain (0.." +
                  std::to_string(num_cameras - 1) + ")");
    }
    if (!selection.empty() && id <= selection.back()) {
      throw Error("--cameras: indices must increase without repeats: " + text);
    }
    selection.push_back(static_cast<int>(id));
  }
  if (selection.empty()) throw Error("--cameras: no camera index in '" + text + "'");
  return selection;
}

void SelectCameras(const std::vector<int>& selection,
                   Camchain* camchain,
                   std::vector<Observation>* observations) {
  std::vector<int> new_id(camchain->size(), -1);
  Camchain kept;
  for (size_t k = 0; k < selection.size(); ++k) {
    new_id[selection[k]] = static_cast<int>(k);
    kept.push_back((*camchain)[selection[k]]);
  }
  std::vector<Observation> kept_observations;
  for (Observation o : *observations) {
    if (o.cam_id < 0 || o.cam_id >= static_cast<int>(new_id.size()) || new_id[o.cam_id] < 0) {
      continue;
    }
    o.cam_id = new_id[o.cam_id];
    kept_observations.push_back(o);
  }
  *camchain = std::move(kept);
  *observations = std::move(kept_observations);
}

void CheckEveryCameraObserved(const std::vector<Observation>& observations,
                              const Camchain& camchain,
                              const std::vector<int>& input_ids,
                              const std::string& observations_path) {
  std::vector<bool> seen(camchain.size(), false);
  for (const Observation& o : observations) seen[o.cam_id] = true;
  const auto missing = std::find(seen.begin(), seen.end(), false);
  if (missing == seen.end()) return;
  std::string others;
  for (size_t c = 0; c < seen.size(); ++c) {
    if (!seen[c]) continue;
    others += (others.empty() ? "" : ",") + std::to_string(input_ids[c]);
  }
  const int cam = input_ids[missing - seen.begin()];
  std::string message =
      "cam" + std::to_string(cam) + " has no observations in " + observations_path;
  message += others.empty() ? std::string(": no camera of the camchain is observed")
                            : "; calibrate the others with --cameras " + others;
  throw Error(message);
}

}  // namespace cli
}  // namespace splinecal
