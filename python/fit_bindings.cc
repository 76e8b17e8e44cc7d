// splinecal.fit: `splinecal fit` (calib/fit.h) returning its result.yaml
// (report/command_outputs.h) as a dict, plus the fitted spline and the IMU residuals as arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/calib/fit.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/report/fit_report.h"
#include "splinecal/report/option_names.h"

namespace splinecal {
namespace python {

namespace {

py::dict ImuResidualsDict(const std::vector<FitImuSample>& samples) {
  py::dict dict;
  dict["t_ns"] = TimeColumn(samples);
  dict["gyro_measured"] = Vector3Column(samples, [](const auto& s) { return s.gyro_measured; });
  dict["gyro_fitted"] = Vector3Column(samples, [](const auto& s) { return s.gyro_fitted; });
  dict["accel_measured"] = Vector3Column(samples, [](const auto& s) { return s.accel_measured; });
  dict["accel_fitted"] = Vector3Column(samples, [](const auto& s) { return s.accel_fitted; });
  return dict;
}

py::dict FitFunction(py::handle imu,
                     py::handle poses,
                     py::object imu_yaml,
                     const std::string& imu_noise,
                     double knot_spacing,
                     const std::string& trajectory,
                     double pose_sigma_m,
                     double pose_sigma_rad,
                     bool estimate_time_offset,
                     double max_time_offset,
                     bool estimate_extrinsic,
                     const std::string& bias_model,
                     double bias_knot_spacing,
                     double gravity,
                     const std::string& accel_unit,
                     const std::string& gyro_unit,
                     int threads,
                     py::handle out,
                     py::handle bag,
                     const std::string& imu_topic,
                     const std::string& bag_time) {
  const EstimateArguments arguments{
      knot_spacing, gravity, imu_yaml, imu_noise, accel_unit, gyro_unit, threads, trajectory};
  FitOptions options;
  ApplyEstimateArguments(arguments, &options.model, &options.solver);
  options.pose_sigma_m = PositiveArgument(pose_sigma_m, "pose_sigma_m");
  options.pose_sigma_rad = PositiveArgument(pose_sigma_rad, "pose_sigma_rad");
  options.estimate_time_offset = estimate_time_offset;
  if (!(max_time_offset > 0.0) || !(max_time_offset <= 1e9)) {
    throw py::value_error("max_time_offset: expected (0, 1e9] s, got " +
                          std::to_string(max_time_offset));
  }
  options.max_time_offset_s = max_time_offset;
  options.estimate_extrinsic = estimate_extrinsic;
  if (!ValueNamed(kBiasModelNames, bias_model, &options.model.bias_model)) {
    throw py::value_error("bias_model: expected " + JoinNames(kBiasModelNames, " or ") +
                          ", got '" + bias_model + "'");
  }
  if (!(bias_knot_spacing > 0.0) || !(bias_knot_spacing <= 1e9)) {
    throw py::value_error("bias_knot_spacing: expected (0, 1e9] s, got " +
                          std::to_string(bias_knot_spacing));
  }
  options.model.bias_knot_spacing_s = bias_knot_spacing;

  FitReportInputs inputs;
  const BagImuArguments bag_arguments{bag, imu_topic, bag_time};
  RequiredArgument(poses, "poses");
  inputs.imu_path = ImuSourceName(imu, bag_arguments);
  inputs.poses_path = AsPath(poses).value_or("");
  inputs.imu_yaml_path = ImuYamlPath(arguments);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  const std::vector<ImuSample> samples =
      ImuInUnits(imu, bag_arguments, arguments.accel_unit, arguments.gyro_unit);
  const std::vector<StampedPose> stamped = StampedPoses(poses, "poses");

  const FitResult result =
      RunInterruptible(&options.solver, [&] { return Fit(samples, stamped, options); });
  py::dict dict = FinishOutputs(output.get(), FitOutputFiles(result, inputs));
  dict["se3_spline"] = py::cast(result.MakeSpline());
  dict["imu_residuals"] = ImuResidualsDict(result.imu_samples);
  return dict;
}

}  // namespace

void BindFit(py::module_& m) {
  const FitOptions defaults;
  const EstimateArguments shared;  // the keywords fit and calibrate share
  DefImuCommand(
      m,
      "fit",
      &FitFunction,
      R"(The continuous-time fit of `splinecal fit`, with its flags as keywords. imu: a EuRoC
imu0/data.csv path or {t_ns, gyro, accel}; poses: a EuRoC ground truth / TUM path or
{t_ns, T_w_s (n, 4, 4)}. out: a folder to write the command's files to (result.yaml,
spline.csv, residuals.csv, pose_residuals.csv, report.html). Returns result.yaml's keys plus
se3_spline (SE3Spline) and imu_residuals {t_ns, gyro_measured, gyro_fitted, accel_measured,
accel_fitted}. Ctrl-C stops the solve (KeyboardInterrupt).)",
      py::arg("imu") = py::none(),
      py::arg("poses") = py::none(),
      py::kw_only(),
      py::arg("imu_yaml") = py::none(),
      py::arg("imu_noise") = shared.imu_noise,
      py::arg("knot_spacing") = shared.knot_spacing,
      py::arg("trajectory") = shared.trajectory,
      py::arg("pose_sigma_m") = defaults.pose_sigma_m,
      py::arg("pose_sigma_rad") = defaults.pose_sigma_rad,
      py::arg("estimate_time_offset") = defaults.estimate_time_offset,
      py::arg("max_time_offset") = defaults.max_time_offset_s,
      py::arg("estimate_extrinsic") = defaults.estimate_extrinsic,
      py::arg("bias_model") = "constant",
      py::arg("bias_knot_spacing") = defaults.model.bias_knot_spacing_s,
      py::arg("gravity") = shared.gravity,
      py::arg("accel_unit") = shared.accel_unit,
      py::arg("gyro_unit") = shared.gyro_unit,
      py::arg("threads") = shared.threads);
}

}  // namespace python
}  // namespace splinecal
