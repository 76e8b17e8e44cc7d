// `splinecal intrinsics`: camera intrinsics and the rig's camera-to-camera extrinsics from
// target observations (intrinsics/calibrate_intrinsics.h, docs/intrinsics.md).
#include <gflags/gflags.h>

#include <algorithm>
#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/camera/observation_gates.h"
#include "splinecal/enum_names.h"
#include "splinecal/error.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/camera_specs.h"
#include "splinecal/intrinsics/compare_models.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/command_outputs.h"
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
              "After the first solve a corner is removed when its error exceeds this many "
              "robust sigmas of the model's fit and its pixel is as far from its neighbours on "
              "the target (a corner the model misfits stays); 0: none is removed");
DEFINE_bool(keep_repeated_views,
            false,
            "Keep views that repeat an earlier view of the same camera (by default set aside: a "
            "camera held still would weigh its one view many times)");
DEFINE_bool(compare_models,
            false,
            "Also fit pinhole-radtan, pinhole-equi and ds-none to the corners used (exact least "
            "squares) and print their RMS and sums of squares; report.html shows each model's "
            "errors by image position");
DEFINE_string(target_deformation,
              "none",
              "The target's geometry estimated with the intrinsics, shared by every view: none "
              "(as the target file says), quadratic or cubic (a surface out of the plane), "
              "in-plane (an aprilgrid's x/y anisotropy e1, shear e2 and tag side to pitch d) or "
              "in-plane-per-view (e1, e2 shared, each timestamp its own d)");
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

IntrinsicsInputs ReadIntrinsicsInputs() {
  const std::string& observations_path = RequiredFlag("observations", FLAGS_observations);
  RequiredFlag("target", FLAGS_target);
  RequiredFlag("models", FLAGS_models);
  RequiredFlag("out", FLAGS_out);
  IntrinsicsInputs in;
  in.options.huber_px = NonNegativeFlag("huber", FLAGS_huber);
  if (FLAGS_min_corners < 6) throw Error("--min-corners: must be at least 6 for a target pose");
  in.options.min_corners = FLAGS_min_corners;
  if (FLAGS_max_views < 0) throw Error("--max-views: must be 0 (all) or positive");
  in.options.max_views_per_camera = FLAGS_max_views;
  in.options.solver.num_threads = ThreadsFlag();

  in.options.outlier_sigmas = NonNegativeFlag("outlier_sigmas", FLAGS_outlier_sigmas);
  in.options.keep_repeated_views = FLAGS_keep_repeated_views;
  if (!ValueNamed(
          kTargetDeformationKinds, FLAGS_target_deformation, &in.options.target_deformation)) {
    throw Error("--target-deformation: expected " + JoinNames(kTargetDeformationKinds, ", ") +
                ", got '" + FLAGS_target_deformation + "'");
  }

  in.target = ReadTargetYaml(FLAGS_target);
  in.observations = ReadObservationsCsv(observations_path);
  in.cameras = IntrinsicsCameraSpecs(
      FLAGS_models, FLAGS_resolution, FLAGS_camchain, FLAGS_cameras, &in.observations);
  CheckIntrinsicsCameraIds(in.observations, in.cameras.size(), observations_path);
  // The library checks again (CalibrateIntrinsics); here the message names the files.
  std::vector<Camera> cameras;
  for (const IntrinsicsCameraSpec& spec : in.cameras) cameras.push_back(spec.camera);
  CheckObservationInputs(
      in.observations,
      &in.target,
      cameras,
      {observations_path,
       FLAGS_target,
       FLAGS_resolution.empty() ? FLAGS_camchain : "--resolution " + FLAGS_resolution});
  // The library checks again (CalibrateIntrinsics); here before the solve, naming the file: in
  // plane needs an aprilgrid, every kind a target in its plane.
  try {
    MakeTargetShape(in.target, in.options.target_deformation);
  } catch (const Error& e) {
    throw Error("--target-deformation: " + FLAGS_target + ": " + e.what());
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
  IntrinsicsReportInputs inputs{FLAGS_observations, FLAGS_target, FLAGS_camchain};
  std::vector<ModelFit> fits;
  if (FLAGS_compare_models) {
    Progress("intrinsics: fitting pinhole-radtan, pinhole-equi and ds-none to the same corners");
    fits = CompareModels(result, in.target, in.cameras, in.options);
    inputs.model_comparison = &fits;
  }
  output.WriteFiles(IntrinsicsOutputFiles(result, inputs));
  output.Commit();
  if (!Quiet()) {
    std::fputs(IntrinsicsSummaryText(result).c_str(), stderr);
    if (FLAGS_compare_models) std::fputs(ModelComparisonText(fits).c_str(), stderr);
  }
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
      "[--cameras I,J] [--huber PX] [--outlier-sigmas N] [--keep-repeated-views] "
      "[--compare-models] [--target-deformation KIND] [--threads N] --out DIR";
  command.description =
      "Calibrates every camera of observations.csv (from `splinecal detect`) with its model of "
      "--models (Kalibr's names), all cameras in one problem with the rig's camera-to-camera "
      "poses. Starts from a sweep over focal lengths and model shapes (works for fisheye and "
      "omnidirectional lenses), drops views that repeat earlier ones and outlier corners, and "
      "reports what it used; --compare-models fits pinhole-radtan, pinhole-equi and ds-none to "
      "the same corners. Writes camchain.yaml (Kalibr's keys, T_cn_cnm1 from cam1 on), "
      "result.yaml (per camera: intrinsics and distortion with stds, RMS, views) and "
      "report.html. With --camchain a camera of the same model starts from its values. "
      "--target-deformation estimates the target's geometry with the intrinsics (result.yaml's "
      "target_deformation; calibrate still reads the target file). See docs/intrinsics.md.";
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
                   {"compare_models", ""},
                   {"target_deformation", ""},
                   {"threads", "", "2"},
                   {"out", ""},
                   {"quiet", ""}};
  command.run = &RunIntrinsics;
  command.read_inputs = [] { ReadIntrinsicsInputs(); };
  return command;
}

}  // namespace cli
}  // namespace splinecal
