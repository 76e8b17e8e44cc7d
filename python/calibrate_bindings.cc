// splinecal.calibrate: `splinecal calibrate` (calib/calibrate_run.h) with every flag as a
// keyword, returning its result.yaml (report/command_outputs.h) as a dict plus the estimated
// spline; the cameras are chosen as the command chooses them (calib/camera_selection.h).
#include <pybind11/pybind11.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/calib/calibrate_run.h"
#include "splinecal/calib/camera_selection.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/camchain_yaml_covariance.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/command_outputs.h"

namespace splinecal {
namespace python {

namespace {

// The IMUs of a rig (docs/calibrate.md, "Several IMUs"): a list or tuple of sources (paths or
// {t_ns, gyro, accel}), or a path text "a.csv,b.csv" as --imu takes it; one source otherwise.
std::vector<py::object> ImuSources(py::handle imu) {
  std::vector<py::object> sources;
  if (py::isinstance<py::list>(imu) || py::isinstance<py::tuple>(imu)) {
    for (py::handle item : imu) sources.push_back(py::reinterpret_borrow<py::object>(item));
  } else if (py::isinstance<py::str>(imu) && imu.cast<std::string>().find(',') != std::string::npos) {
    for (const std::string& path : SplitCommaList(imu.cast<std::string>(), "imu", "path")) {
      sources.push_back(py::str(path));
    }
  } else {
    sources.push_back(py::reinterpret_borrow<py::object>(imu));
  }
  return sources;
}

// One entry per IMU of a comma list (or a list) given once for all or once per IMU, as the
// command's --imu-yaml and --imu-model (a str split at commas, a path, or a list of str or paths);
// ValueError naming the keyword otherwise.
std::vector<std::string> PerImu(py::handle value, const std::string& name, size_t num_imus) {
  std::vector<std::string> entries;
  if (py::isinstance<py::list>(value) || py::isinstance<py::tuple>(value)) {
    for (py::handle item : value) entries.push_back(PathArgument(item, name));  // str or PathLike
  } else if (py::isinstance<py::str>(value)) {
    entries = SplitCommaList(value.cast<std::string>(), name, "entry");
  } else {
    entries = {PathArgument(value, name)};
  }
  if (entries.empty() || (entries.size() != 1 && entries.size() != num_imus)) {
    throw py::value_error(name + ": " + std::to_string(entries.size()) + " entries for " +
                          std::to_string(num_imus) + " IMU(s): give one for all or one per IMU");
  }
  entries.resize(num_imus, entries.front());
  return entries;
}

py::dict CalibrateFunction(py::handle imu,
                           py::handle observations,
                           py::handle camchain,
                           py::handle target,
                           py::handle cameras,
                           py::handle initial_poses,
                           py::object imu_yaml,
                           const std::string& imu_noise,
                           bool rolling_shutter,
                           const std::string& imu_model,
                           const std::string& intrinsics,
                           const std::string& camera_chain,
                           const std::string& target_scale,
                           bool hold_camera_chain,
                           bool estimate_intrinsics,
                           bool no_time_offset,
                           double knot_spacing,
                           const std::string& trajectory,
                           double pixel_sigma,
                           double huber,
                           int min_corners,
                           double gravity,
                           const std::string& accel_unit,
                           const std::string& gyro_unit,
                           int threads,
                           py::handle out,
                           py::handle bag,
                           const std::string& imu_topic,
                           const std::string& bag_time) {
  // Several IMUs: imu (or the bag's imu_topic) lists them, the first the reference; imu_yaml and
  // imu_model give one entry for all or one per IMU (the command's lists).
  const std::vector<py::object> imu_sources =
      bag.is_none() ? ImuSources(imu) : std::vector<py::object>{py::reinterpret_borrow<py::object>(imu)};
  const std::vector<std::string> topics = SplitCommaList(imu_topic, "imu_topic", "topic");
  const size_t num_imus = bag.is_none() ? imu_sources.size() : topics.size();
  const std::vector<std::string> yamls =
      imu_yaml.is_none() ? std::vector<std::string>(num_imus) : PerImu(imu_yaml, "imu_yaml", num_imus);
  const std::vector<std::string> models = PerImu(py::str(imu_model), "imu_model", num_imus);
  const EstimateArguments arguments{knot_spacing,
                                    gravity,
                                    yamls[0].empty() ? py::object(py::none()) : py::str(yamls[0]),
                                    imu_noise,
                                    accel_unit,
                                    gyro_unit,
                                    threads,
                                    trajectory};
  CalibrateOptions options;
  ApplyEstimateArguments(arguments, &options.model, &options.solver);
  options.rolling_shutter = rolling_shutter;
  std::vector<ImuModelKind> kinds(num_imus, ImuModelKind::kCalibrated);
  for (size_t i = 0; i < num_imus; ++i) {
    if (!ParseImuModelKind(models[i], &kinds[i])) {
      throw py::value_error("imu_model: '" + models[i] + "' is not one of " + ImuModelNames());
    }
  }
  options.imu_model = kinds[0];
  options.estimate_time_offset = !no_time_offset;
  options.intrinsics = ParseParameterMode(
      "intrinsics", intrinsics, estimate_intrinsics, ParameterMode::kFree, "estimate_intrinsics");
  options.camera_chain = ParseParameterMode(
      "camera_chain", camera_chain, hold_camera_chain, ParameterMode::kHeld, "hold_camera_chain");
  options.target_scale = ParseTargetScaleMode("target_scale", target_scale);
  options.command_line = "splinecal.calibrate (Python)";
  options.pixel_sigma_px = NonNegativeArgument(pixel_sigma, "pixel_sigma");
  options.huber_px = NonNegativeArgument(huber, "huber");
  if (min_corners < 4) throw py::value_error("min_corners: must be at least 4");
  options.min_corners_per_frame = min_corners;
  if (target.is_none() && initial_poses.is_none()) {
    throw py::value_error(
        "target, initial_poses: without a target, initial_poses is needed (the IMU trajectory, "
        "e.g. splinecal.align on SLAM poses)");
  }

  CalibrateReportInputs inputs;
  RequiredArgument(observations, "observations");
  RequiredArgument(camchain, "camchain");
  const BagImuArguments first_bag{bag, topics.front(), bag_time};
  inputs.imu_path = ImuSourceName(imu_sources.front(), first_bag);
  inputs.observations_path = AsPath(observations).value_or("");
  inputs.camchain_path = PathArgument(camchain, "camchain");
  inputs.target_path = target.is_none() ? "" : PathArgument(target, "target");
  inputs.initial_poses_path = AsPath(initial_poses).value_or("");
  inputs.imu_yaml_path = ImuYamlPath(arguments);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);

  Camchain rig = ReadCamchainYaml(inputs.camchain_path);
  std::unique_ptr<CalibrationTarget> board;
  if (!target.is_none()) {
    board = std::make_unique<CalibrationTarget>(ReadTargetYaml(inputs.target_path));
  }
  std::vector<Observation> points = Observations(observations);
  if (!target.is_none()) options.target_name = inputs.target_path;
  SelectCalibrationCameras(CommaListArgument(cameras, "cameras"),
                           inputs.camchain_path,
                           inputs.observations_path.empty() ? "observations"
                                                            : inputs.observations_path,
                           ReadCamchainCovariances(inputs.camchain_path, rig),
                           &rig,
                           &points,
                           &options);
  const std::vector<ImuSample> samples =
      ImuInUnits(imu_sources.front(), first_bag, arguments.accel_unit, arguments.gyro_unit);
  for (size_t i = 1; i < num_imus; ++i) {
    const BagImuArguments bag_i{bag, bag.is_none() ? "" : topics[i], bag_time};
    py::handle source = bag.is_none() ? py::handle(imu_sources[i]) : py::handle(py::none());
    FurtherImu further;
    further.name = ImuSourceName(source, bag_i, "imu" + std::to_string(i));
    further.samples = ImuInUnits(source, bag_i, arguments.accel_unit, arguments.gyro_unit);
    further.noise = yamls[i].empty() ? ImuNoise::Adis16448() : ReadImuYaml(yamls[i]);
    further.model = kinds[i];
    options.further_imus.push_back(std::move(further));
  }
  std::vector<StampedPose> initial;
  if (!initial_poses.is_none()) initial = StampedPoses(initial_poses, "initial_poses");

  const CalibrationResult result = RunInterruptible(&options.solver, [&] {
    return CalibrateWithInitialPoses(samples, points, rig, board.get(), initial, options);
  });
  py::dict dict = FinishOutputs(output.get(), CalibrateOutputFiles(result, options, inputs));
  dict["se3_spline"] = py::cast(result.MakeSpline());
  return dict;
}

}  // namespace

void BindCalibrate(py::module_& m) {
  const CalibrateOptions defaults;
  const EstimateArguments shared;  // the keywords fit and calibrate share
  DefImuCommand(
      m,
      "calibrate",
      &CalibrateFunction,
      R"(Camera-IMU calibration as `splinecal calibrate`, with its flags as keywords. imu: a
EuRoC imu0/data.csv path or {t_ns, gyro, accel}; observations: an observations.csv path or
{t_ns, cam_id, point_id, uv}; camchain and target: Kalibr YAML paths (target None: natural
landmarks only, which needs initial_poses: a EuRoC ground truth / TUM path or {t_ns, T_w_s});
cameras: "0,2" or [0, 2] (default: all); intrinsics: "held", "prior", "consider" or "free";
camera_chain: "held", "prior" or "free" ("": the camchain decides, docs/calibrate.md); target_scale: "check", "free" or "held";
imu_model: Kalibr's "calibrated", "scale-misalignment" or "scale-misalignment-size-effect"
(docs/imu_models.md). Several IMUs of one rig (docs/calibrate.md, "Several IMUs"): imu a list of
sources or "a.csv,b.csv" (with bag: imu_topic "/imu0,/imu1"), the first the reference; imu_yaml
and imu_model one for all or one per IMU (a list or comma-separated). out: a folder to write the command's files to (camchain-imucam.yaml,
result.yaml, reprojection_errors.csv, spline.csv, report.html; imu_models.yaml with a model).
Returns result.yaml's keys plus se3_spline (SE3Spline). Ctrl-C stops the solve
(KeyboardInterrupt).)",
      py::arg("imu") = py::none(),
      py::arg("observations") = py::none(),
      py::arg("camchain") = py::none(),
      py::arg("target") = py::none(),
      py::kw_only(),
      py::arg("cameras") = "",
      py::arg("initial_poses") = py::none(),
      py::arg("imu_yaml") = py::none(),
      py::arg("imu_noise") = shared.imu_noise,
      py::arg("rolling_shutter") = defaults.rolling_shutter,
      py::arg("imu_model") = "calibrated",
      py::arg("intrinsics") = "",
      py::arg("camera_chain") = "",
      py::arg("target_scale") = "check",
      py::arg("hold_camera_chain") = false,
      py::arg("estimate_intrinsics") = false,
      py::arg("no_time_offset") = false,
      py::arg("knot_spacing") = defaults.model.knot_spacing_s,
      py::arg("trajectory") = shared.trajectory,
      py::arg("pixel_sigma") = defaults.pixel_sigma_px,
      py::arg("huber") = defaults.huber_px,
      py::arg("min_corners") = defaults.min_corners_per_frame,
      py::arg("gravity") = shared.gravity,
      py::arg("accel_unit") = shared.accel_unit,
      py::arg("gyro_unit") = shared.gyro_unit,
      py::arg("threads") = shared.threads);
}

}  // namespace python
}  // namespace splinecal
