#include "splinecal/calib/camera_selection.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

#include "splinecal/error.h"

namespace splinecal {

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
  // cam_overlaps name cameras by their index: renumber them, and drop the cameras left out.
  for (CameraCalibration& calibration : kept) {
    std::vector<int> overlaps;
    for (int other : calibration.cam_overlaps) {
      if (other >= 0 && other < static_cast<int>(new_id.size()) && new_id[other] >= 0) {
        overlaps.push_back(new_id[other]);
      }
    }
    calibration.cam_overlaps = std::move(overlaps);
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

std::vector<SE3d> HeldCameraChain(const Camchain& camchain,
                                  const std::vector<int>& selection,
                                  const std::string& camchain_path,
                                  const std::string& why) {
  // T_cn_c0 of every camera from the T_cn_cnm1 chain, then relative to the first selected.
  std::vector<SE3d> T_n_0 = {SE3d()};
  for (size_t n = 1; n < camchain.size(); ++n) {
    if (!camchain[n].T_cn_cnm1) {
      throw Error(camchain_path,
                  0,
                  why + ": cam" + std::to_string(n) +
                      " has no T_cn_cnm1 (the camera chain `splinecal intrinsics` writes)");
    }
    T_n_0.push_back(*camchain[n].T_cn_cnm1 * T_n_0.back());
  }
  std::vector<int> chosen = selection;
  if (chosen.empty()) {
    for (size_t n = 0; n < camchain.size(); ++n) chosen.push_back(static_cast<int>(n));
  }
  std::vector<SE3d> T_cn_c0;
  for (int n : chosen) T_cn_c0.push_back(T_n_0[n] * T_n_0[chosen.front()].inverse());
  return T_cn_c0;
}

std::vector<std::optional<CameraCovariance>> SelectCovariances(
    const std::vector<std::optional<CameraCovariance>>& all, const std::vector<int>& selection) {
  if (selection.empty() || all.empty()) return all;
  std::vector<std::optional<CameraCovariance>> chosen;
  for (size_t k = 0; k < selection.size(); ++k) {
    std::optional<CameraCovariance> covariance = all[selection[k]];
    const bool consecutive = k > 0 && selection[k - 1] == selection[k] - 1;
    if (covariance && covariance->has_T_cn_cnm1 && !consecutive) {
      const int n = static_cast<int>(covariance->intrinsics.size());
      covariance->matrix = Eigen::MatrixXd(covariance->matrix.topLeftCorner(n, n));
      covariance->has_T_cn_cnm1 = false;
    }
    chosen.push_back(covariance);
  }
  return chosen;
}

std::optional<ParameterMode> ParseParameterMode(const std::string& flag,
                                                const std::string& value,
                                                bool alias,
                                                ParameterMode alias_mode,
                                                const std::string& alias_flag) {
  std::optional<ParameterMode> mode;
  if (!value.empty()) {
    for (ParameterMode m : {ParameterMode::kHeld, ParameterMode::kPrior, ParameterMode::kFree,
                            ParameterMode::kConsider}) {
      if (value == ParameterModeName(m)) mode = m;
    }
    if (!mode) {
      throw Error(flag + ": expected held, prior, consider or free, got '" + value + "'");
    }
  }
  if (!alias) return mode;
  if (mode && *mode != alias_mode) {
    throw Error(alias_flag + " contradicts " + flag + " " + ParameterModeName(*mode));
  }
  return alias_mode;
}

TargetScaleMode ParseTargetScaleMode(const std::string& flag, const std::string& value) {
  for (TargetScaleMode mode :
       {TargetScaleMode::kCheck, TargetScaleMode::kFree, TargetScaleMode::kHeld}) {
    if (value == TargetScaleModeName(mode)) return mode;
  }
  throw Error(flag + ": expected check, free or held, got '" + value + "'");
}

void SelectCalibrationCameras(const std::string& cameras,
                              const std::string& camchain_path,
                              const std::string& observations_path,
                              const std::vector<std::optional<CameraCovariance>>& covariances,
                              Camchain* camchain,
                              std::vector<Observation>* observations,
                              CalibrateOptions* options) {
  CheckCameraIds(*observations, *camchain, observations_path, camchain_path);
  const std::vector<int> selection =
      ParseCameraSelection(cameras, static_cast<int>(camchain->size()));
  options->camchain_covariances = SelectCovariances(covariances, selection);
  // The default chain mode is a prior when every selected camera after the first has T_cn_cnm1
  // rows in its covariance (CalibrateOptions::camera_chain).
  const size_t num_selected = selection.empty() ? camchain->size() : selection.size();
  bool chain_rows = num_selected > 1 && options->camchain_covariances.size() == num_selected;
  for (size_t k = 1; chain_rows && k < num_selected; ++k) {
    const std::optional<CameraCovariance>& covariance = options->camchain_covariances[k];
    if (!covariance || !covariance->has_T_cn_cnm1) chain_rows = false;
  }
  const bool wants_chain = options->camera_chain
                               ? *options->camera_chain != ParameterMode::kFree
                               : chain_rows;
  if (wants_chain) {
    const std::string why =
        std::string("--camera-chain ") +
        (options->camera_chain ? ParameterModeName(*options->camera_chain) : "prior");
    options->camera_chain_T_cn_c0 = HeldCameraChain(*camchain, selection, camchain_path, why);
  }
  SelectCameras(selection, camchain, observations);
  CheckEveryCameraObserved(*observations, *camchain, selection, observations_path);
}

}  // namespace splinecal
