#include "splinecal/intrinsics/camera_specs.h"

#include <algorithm>
#include <cstdio>

#include "splinecal/calib/camera_selection.h"
#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Splits at every comma; an empty field is an error naming the flag.
std::vector<std::string> SplitList(const std::string& flag, const std::string& value) {
  std::vector<std::string> items;
  size_t begin = 0;
  while (true) {
    const size_t comma = value.find(',', begin);
    items.push_back(value.substr(begin, comma - begin));
    if (items.back().empty()) throw Error("--" + flag + ": empty entry in '" + value + "'");
    if (comma == std::string::npos) break;
    begin = comma + 1;
  }
  return items;
}

Eigen::Vector2i ParseResolution(const std::string& text) {
  int w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &w, &x, &h, &extra) != 3 || x != 'x' || w <= 0 ||
      h <= 0 || w > 100000 || h > 100000) {
    throw Error("--resolution: '" + text + "' is not WIDTHxHEIGHT in pixels (e.g. 752x480)");
  }
  return Eigen::Vector2i(w, h);
}

}  // namespace

std::vector<IntrinsicsCameraSpec> IntrinsicsCameraSpecs(const std::string& models_text,
                                                        const std::string& resolution,
                                                        const std::string& camchain_path,
                                                        const std::string& cameras_text,
                                                        std::vector<Observation>* observations) {
  if (resolution.empty() == camchain_path.empty()) {
    throw Error("intrinsics needs the image size: give --resolution or --camchain (one of them)");
  }
  if (models_text.empty()) throw Error("--models is required");
  const std::vector<std::string> models = SplitList("models", models_text);
  std::vector<IntrinsicsCameraSpec> cameras;
  for (const std::string& name : models) {
    IntrinsicsCameraSpec spec;
    if (!ParseCameraModelName(name, &spec.camera.projection, &spec.camera.distortion)) {
      throw Error("--models: unknown camera model '" + name +
                  "' (pinhole-none, pinhole-radtan, pinhole-equi, pinhole-fov, omni-none, "
                  "omni-radtan, eucm-none, ds-none)");
    }
    cameras.push_back(spec);
  }
  // The cameras of the input: the camchain's, else those the observations name.
  Camchain camchain;
  if (!camchain_path.empty()) {
    camchain = ReadCamchainYaml(camchain_path);
  } else {
    int num_input_cameras = cameras_text.empty() ? static_cast<int>(models.size()) : 0;
    for (const Observation& o : *observations) {
      num_input_cameras = std::max(num_input_cameras, o.cam_id + 1);
    }
    camchain.resize(num_input_cameras);
  }
  if (!cameras_text.empty()) {
    // --models names the selected cameras only; they become cam0, cam1, ... in this order.
    const std::vector<int> selection =
        ParseCameraSelection(cameras_text, static_cast<int>(camchain.size()));
    SelectCameras(selection, &camchain, observations);
    if (selection.size() != models.size()) {
      throw Error(StringPrintf("--cameras selects %zu camera(s) but --models names %zu: one "
                               "model per selected camera",
                               selection.size(),
                               models.size()));
    }
  }
  if (!resolution.empty()) {
    const std::vector<std::string> sizes = SplitList("resolution", resolution);
    if (sizes.size() != 1 && sizes.size() != models.size()) {
      throw Error(
          StringPrintf("--resolution: %zu sizes for %zu models (give one, or one per "
                       "model)",
                       sizes.size(),
                       models.size()));
    }
    for (size_t n = 0; n < models.size(); ++n) {
      const Eigen::Vector2i size = ParseResolution(sizes.size() == 1 ? sizes[0] : sizes[n]);
      cameras[n].camera.width = size.x();
      cameras[n].camera.height = size.y();
    }
    return cameras;
  }
  if (camchain.size() != models.size()) {
    throw Error(
        camchain_path,
        0,
        StringPrintf(
            "describes %zu camera(s) but --models names %zu", camchain.size(), models.size()));
  }
  for (size_t n = 0; n < models.size(); ++n) {
    const Camera& given = camchain[n].camera;
    IntrinsicsCameraSpec& spec = cameras[n];
    spec.camera.width = given.width;
    spec.camera.height = given.height;
    // The same model: its values are a starting point; another model: only its size is.
    if (given.projection == spec.camera.projection && given.distortion == spec.camera.distortion) {
      spec.camera = given;
      spec.initial_values = true;
    }
  }
  return cameras;
}

void CheckIntrinsicsCameraIds(const std::vector<Observation>& observations,
                              size_t num_models,
                              const std::string& observations_path) {
  for (const Observation& o : observations) {
    if (o.cam_id < 0 || o.cam_id >= static_cast<int>(num_models)) {
      throw Error(observations_path,
                  0,
                  StringPrintf("cam_id %d (frame t_ns %lld) but --models names %zu camera(s): "
                               "one model per camera, cam0 first (or select cameras with "
                               "--cameras)",
                               o.cam_id,
                               static_cast<long long>(o.t_ns),
                               num_models));
    }
  }
}

}  // namespace splinecal
