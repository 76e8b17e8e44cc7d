// `splinecal intrinsics`: camera intrinsics and the rig's camera-to-camera extrinsics from
// target observations (intrinsics/calibrate_intrinsics.h, docs/intrinsics.md).
#include <gflags/gflags.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "camera_selection.h"
#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/intrinsics_report.h"
#include "splinecal/string_printf.h"

DEFINE_string(models,
              "",
              "Camera models, one per camera (cam0 first), comma-separated: pinhole-none, "
              "pinhole-radtan, pinhole-equi, pinhole-fov, omni-none, omni-radtan, eucm-none, "
              "ds-none");
DEFINE_string(resolution,
              "",
              "Image size WxH [px], one per camera or one for all (e.g. 752x480); or give "
              "--camchain");
DEFINE_double(outlier_sigmas,
              5.0,
              "Corners whose error exceeds this many robust pixel sigmas are removed after the "
              "first solve; 0: none is removed");
DEFINE_bool(keep_repeated_views,
            false,
            "Keep views that repeat an earlier view of the same camera (by default set aside: a "
            "camera held still would weigh its one view many times)");
DECLARE_string(cameras);

DEFINE_int32(max_views,
             0,
             "Views per camera at most, evenly thinned over the recording; 0: every view that "
             "does not repeat an earlier one");

namespace splinecal {
namespace cli {
namespace {

struct IntrinsicsInputs {
  std::vector<Observation> observations;
  CalibrationTarget target;
  std::vector<IntrinsicsCameraSpec> cameras;
  IntrinsicsOptions options;
};

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

IntrinsicsInputs ReadIntrinsicsInputs() {
  const std::string& observations_path = RequiredFlag("observations", FLAGS_observations);
  RequiredFlag("target", FLAGS_target);
  RequiredFlag("models", FLAGS_models);
  RequiredFlag("out", FLAGS_out);
  if (FLAGS_resolution.empty() == FLAGS_camchain.empty()) {
    throw Error("intrinsics needs the image size: give --resolution or --camchain (one of them)");
  }
  IntrinsicsInputs in;
  in.options.huber_px = NonNegativeFlag("huber", FLAGS_huber);
  if (FLAGS_min_corners < 6) throw Error("--min-corners: must be at least 6 for a target pose");
  in.options.min_corners = FLAGS_min_corners;
  if (FLAGS_max_views < 0) throw Error("--max-views: must be 0 (all) or positive");
  in.options.max_views_per_camera = FLAGS_max_views;
  in.options.solver.num_threads = ThreadsFlag();

  in.options.outlier_sigmas = NonNegativeFlag("outlier_sigmas", FLAGS_outlier_sigmas);
  in.options.keep_repeated_views = FLAGS_keep_repeated_views;

  const std::vector<std::string> models = SplitList("models", FLAGS_models);
  for (const std::string& name : models) {
    IntrinsicsCameraSpec spec;
    if (!ParseCameraModelName(name, &spec.camera.projection, &spec.camera.distortion)) {
      throw Error("--models: unknown camera model '" + name +
                  "' (pinhole-none, pinhole-radtan, pinhole-equi, pinhole-fov, omni-none, "
                  "omni-radtan, eucm-none, ds-none)");
    }
    in.cameras.push_back(spec);
  }
  in.target = ReadTargetYaml(FLAGS_target);
  in.observations = ReadObservationsCsv(observations_path);
  // The cameras of the input: the camchain's, else those the observations name.
  Camchain camchain;
  if (!FLAGS_camchain.empty()) {
    camchain = ReadCamchainYaml(FLAGS_camchain);
  } else {
    int num_input_cameras = FLAGS_cameras.empty() ? static_cast<int>(models.size()) : 0;
    for (const Observation& o : in.observations) {
      num_input_cameras = std::max(num_input_cameras, o.cam_id + 1);
    }
    camchain.resize(num_input_cameras);
  }
  if (!FLAGS_cameras.empty()) {
    // --models names the selected cameras only; they become cam0, cam1, ... in this order.
    const std::vector<int> selection =
        ParseCameraSelection(FLAGS_cameras, static_cast<int>(camchain.size()));
    SelectCameras(selection, &camchain, &in.observations);
    if (selection.size() != models.size()) {
      throw Error(StringPrintf("--cameras selects %zu camera(s) but --models names %zu: one "
                               "model per selected camera",
                               selection.size(),
                               models.size()));
    }
  }
  if (!FLAGS_resolution.empty()) {
    const std::vector<std::string> sizes = SplitList("resolution", FLAGS_resolution);
    if (sizes.size() != 1 && sizes.size() != models.size()) {
      throw Error(
          StringPrintf("--resolution: %zu sizes for %zu models (give one, or one per "
                       "model)",
                       sizes.size(),
                       models.size()));
    }
    for (size_t n = 0; n < models.size(); ++n) {
      const Eigen::Vector2i size = ParseResolution(sizes.size() == 1 ? sizes[0] : sizes[n]);
      in.cameras[n].camera.width = size.x();
      in.cameras[n].camera.height = size.y();
    }
  } else {
    if (camchain.size() != models.size()) {
      throw Error(
          FLAGS_camchain,
          0,
          StringPrintf(
              "describes %zu camera(s) but --models names %zu", camchain.size(), models.size()));
    }
    for (size_t n = 0; n < models.size(); ++n) {
      const Camera& given = camchain[n].camera;
      IntrinsicsCameraSpec& spec = in.cameras[n];
      spec.camera.width = given.width;
      spec.camera.height = given.height;
      // The same model: its values are a starting point; another model: only its size is.
      if (given.projection == spec.camera.projection &&
          given.distortion == spec.camera.distortion) {
        spec.camera = given;
        spec.initial_values = true;
      }
    }
  }
  for (const Observation& o : in.observations) {
    if (o.cam_id < 0 || o.cam_id >= static_cast<int>(models.size())) {
      throw Error(observations_path,
                  0,
                  StringPrintf("cam_id %d (frame t_ns %lld) but --models names %zu camera(s): "
                               "one model per camera, cam0 first (or select cameras with "
                               "--cameras)",
                               o.cam_id,
                               static_cast<long long>(o.t_ns),
                               models.size()));
    }
  }
  return in;
}

int RunIntrinsics() {
  IntrinsicsInputs in = ReadIntrinsicsInputs();
  OutputDir output(FLAGS_out);
  Progress(StringPrintf(
      "intrinsics: %zu observations, %zu camera(s)", in.observations.size(), in.cameras.size()));
  in.options.solver.progress = [](const std::string& line) { Progress(line); };
  const IntrinsicsResult result =
      CalibrateIntrinsics(in.observations, in.target, in.cameras, in.options);

  Camchain camchain;
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    CameraCalibration calibration;
    calibration.camera = result.cameras[n].camera;
    if (n > 0) calibration.T_cn_cnm1 = result.cameras[n].T_cn_cnm1;
    camchain.push_back(calibration);
  }
  std::vector<ParameterCovariance> covariances;
  for (const IntrinsicsCameraResult& camera : result.cameras) {
    covariances.push_back(camera.covariance);
  }
  output.WriteFile("camchain.yaml",
                   CamchainYamlText(camchain, CamchainKeys::kCamerasOnly, covariances));
  output.WriteFile("result.yaml", IntrinsicsResultYaml(result));
  IntrinsicsReportInputs inputs{FLAGS_observations, FLAGS_target, FLAGS_camchain};
  output.WriteFile("report.html", IntrinsicsReportHtml(result, inputs, 3000));
  output.Commit();
  if (!Quiet()) std::fputs(IntrinsicsSummaryText(result).c_str(), stderr);
  return 0;
}

}  // namespace

Command IntrinsicsCommand() {
  Command command;
  command.name = "intrinsics";
  command.summary = "camera intrinsics and camera-to-camera extrinsics from target corners";
  command.usage =
      "splinecal intrinsics --observations FILE --target FILE --models M0[,M1...] "
      "(--resolution WxH[,WxH...] | --camchain FILE) [--max-views N] [--min-corners N] "
      "[--cameras I,J] [--huber PX] [--outlier-sigmas N] [--keep-repeated-views] [--threads N] "
      "--out DIR";
  command.description =
      "Calibrates every camera of observations.csv (from `splinecal detect`) with its model of "
      "--models (Kalibr's names), all cameras in one problem with the rig's camera-to-camera "
      "poses. Starts from a sweep over focal lengths and model shapes (works for fisheye and "
      "omnidirectional lenses), drops views that repeat earlier ones and outlier corners, and "
      "reports what it used. Writes camchain.yaml (Kalibr's keys, T_cn_cnm1 from cam1 on), "
      "result.yaml (per camera: intrinsics and distortion with stds, RMS, views) and "
      "report.html. With --camchain a camera of the same model starts from its values. See "
      "docs/intrinsics.md.";
  command.flags = {{"observations", ""},
                   {"target",
                    "Calibration target: Kalibr aprilgrid, checkerboard or points YAML "
                    "[path]"},
                   {"models", ""},
                   {"resolution", ""},
                   {"camchain",
                    "Kalibr camchain.yaml giving each camera's image size (and a "
                    "starting point for a camera of the same model) [path]"},
                   {"cameras",
                    "Calibrate only these cameras of the observations (or of --camchain), "
                    "comma-separated indices in increasing order; --models names one model per "
                    "selected camera and the output numbers them cam0, cam1, ... Default: all"},
                   {"max_views", ""},
                   {"min_corners", "Views with fewer target corners are not used", "12"},
                   {"huber",
                    "Huber threshold [px] of the first solve, before outliers are "
                    "removed; 0 disables it"},
                   {"outlier_sigmas", ""},
                   {"keep_repeated_views", ""},
                   {"threads", "", "2"},
                   {"out", ""},
                   {"quiet", ""}};
  command.run = &RunIntrinsics;
  command.read_inputs = [] { ReadIntrinsicsInputs(); };
  return command;
}

}  // namespace cli
}  // namespace splinecal
