// splinecal.intrinsics: `splinecal intrinsics` (intrinsics/calibrate_intrinsics.h) with every
// flag as a keyword, the cameras read as the command reads them (intrinsics/camera_specs.h),
// returning its result.yaml (report/command_outputs.h) as a dict plus its camchain.yaml.
#include <pybind11/pybind11.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/enum_names.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/camera_specs.h"
#include "splinecal/intrinsics/compare_models.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/command_outputs.h"

namespace splinecal {
namespace python {

namespace {

py::dict IntrinsicsFunction(py::handle observations,
                            py::handle target,
                            py::handle models,
                            py::handle resolution,
                            py::handle camchain,
                            py::handle cameras,
                            double outlier_sigmas,
                            bool keep_repeated_views,
                            bool compare_models,
                            const std::string& target_deformation,
                            int max_views,
                            int min_corners,
                            double huber,
                            int threads,
                            py::handle out) {
  IntrinsicsOptions options;
  options.huber_px = NonNegativeArgument(huber, "huber");
  if (min_corners < 6) throw py::value_error("min_corners: must be at least 6 for a target pose");
  options.min_corners = min_corners;
  if (max_views < 0) throw py::value_error("max_views: must be 0 (all) or positive");
  options.max_views_per_camera = max_views;
  options.outlier_sigmas = NonNegativeArgument(outlier_sigmas, "outlier_sigmas");
  options.keep_repeated_views = keep_repeated_views;
  if (!ValueNamed(kTargetDeformationKinds, target_deformation, &options.target_deformation)) {
    throw py::value_error("target_deformation: expected " +
                          JoinNames(kTargetDeformationKinds, ", ") + ", got '" +
                          target_deformation + "'");
  }
  if (threads < 1 || threads > 256) {
    throw py::value_error("threads: expected 1 to 256, got " + std::to_string(threads));
  }
  options.solver.num_threads = threads;

  IntrinsicsReportInputs inputs;
  inputs.observations_path = AsPath(observations).value_or("");
  inputs.target_path = PathArgument(target, "target");
  inputs.camchain_path = camchain.is_none() ? "" : PathArgument(camchain, "camchain");
  std::vector<Observation> points = Observations(observations);
  const std::vector<IntrinsicsCameraSpec> specs = IntrinsicsCameraSpecs(
      CommaListArgument(models, "models"),
      resolution.is_none() ? "" : CommaListArgument(resolution, "resolution"),
      inputs.camchain_path,
      CommaListArgument(cameras, "cameras"),
      &points);
  const CalibrationTarget board = ReadTargetYaml(inputs.target_path);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  CheckIntrinsicsCameraIds(
      points, specs.size(), inputs.observations_path.empty() ? "observations"
                                                             : inputs.observations_path);

  const IntrinsicsResult result = RunInterruptible(
      &options.solver, [&] { return CalibrateIntrinsics(points, board, specs, options); });
  std::vector<ModelFit> fits;
  if (compare_models) {
    fits = RunInterruptible(&options.solver,
                            [&] { return CompareModels(result, board, specs, options); });
    inputs.model_comparison = &fits;
  }
  const std::vector<OutputFile> files = IntrinsicsOutputFiles(result, inputs);
  py::dict dict = FinishOutputs(output.get(), files);
  dict["camchain_yaml"] = OutputFileContents(files, "camchain.yaml");
  if (result.target_deformation.shape.per_point()) {
    dict["target_yaml"] = OutputFileContents(files, "target.yaml");
  }
  return dict;
}

}  // namespace

void BindIntrinsics(py::module_& m) {
  const IntrinsicsOptions defaults;
  DefCommand(
      m,
      "intrinsics",
      &IntrinsicsFunction,
      R"(Camera intrinsics and camera-to-camera extrinsics as `splinecal intrinsics`, with its
flags as keywords. observations: an observations.csv path or {t_ns, cam_id, point_id, uv};
target: a Kalibr target YAML path; models: "pinhole-radtan,pinhole-equi" or a list, one per
camera (cam0 first); the image size from resolution ("752x480", one for all or one per camera,
or a list) or from camchain (a camchain.yaml path), one of the two; cameras: "0,2" or [0, 2] selects
input cameras (models then names those); outlier_sigmas 0 removes no corner; compare_models also
fits pinhole-radtan, pinhole-equi and ds-none to the corners used (result's model_comparison);
target_deformation: "none", "quadratic", "cubic", "in-plane", "in-plane-per-view", "points" or
"points-in-plane", the target's geometry estimated with the intrinsics (result's
target_deformation). out: a folder to write camchain.yaml, result.yaml and report.html (and
view_inset.csv with in-plane-per-view; target.yaml and target_points.csv with points) to.
Returns result.yaml's keys plus camchain_yaml (the text of camchain.yaml, Kalibr's keys:
calibrate's camchain) and, with points, target_yaml (the refined target: calibrate's target).)",
      py::arg("observations"),
      py::arg("target"),
      py::arg("models"),
      py::kw_only(),
      py::arg("resolution") = py::none(),
      py::arg("camchain") = py::none(),
      py::arg("cameras") = "",
      py::arg("outlier_sigmas") = defaults.outlier_sigmas,
      py::arg("keep_repeated_views") = defaults.keep_repeated_views,
      py::arg("compare_models") = false,
      py::arg("target_deformation") = TargetDeformationName(defaults.target_deformation),
      py::arg("max_views") = defaults.max_views_per_camera,
      py::arg("min_corners") = defaults.min_corners,
      py::arg("huber") = defaults.huber_px,
      py::arg("threads") = 2);
}

}  // namespace python
}  // namespace splinecal
