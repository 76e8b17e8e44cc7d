// splinecal.calibrate: `splinecal calibrate` (calib/calibrate.h) with a target, returning its
// result.yaml (report/calibrate_report.h) as a dict plus the estimated spline.
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/calibrate_report.h"
#include "yaml_to_python.h"

namespace splinecal {
namespace python {

namespace {

py::dict CalibrateFunction(py::handle imu,
                           py::handle observations,
                           py::handle camchain,
                           py::handle target,
                           py::object imu_yaml,
                           const std::string& imu_noise,
                           bool rolling_shutter,
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
                           int threads) {
  const EstimateArguments arguments{
      knot_spacing, gravity, imu_yaml, imu_noise, accel_unit, gyro_unit, threads, trajectory};
  CalibrateOptions options;
  ApplyEstimateArguments(arguments, &options.model, &options.solver);
  options.rolling_shutter = rolling_shutter;
  options.estimate_time_offset = !no_time_offset;
  options.estimate_intrinsics = estimate_intrinsics;
  options.pixel_sigma_px = NonNegativeArgument(pixel_sigma, "pixel_sigma");
  options.huber_px = NonNegativeArgument(huber, "huber");
  if (min_corners < 4) throw py::value_error("min_corners: must be at least 4");
  options.min_corners_per_frame = min_corners;

  const Camchain rig = ReadCamchainYaml(PathArgument(camchain, "camchain"));
  const CalibrationTarget board = ReadTargetYaml(PathArgument(target, "target"));
  const std::vector<Observation> points = Observations(observations);
  const std::vector<ImuSample> samples = ImuInUnits(imu, arguments);

  const CalibrationResult result = RunInterruptible(
      &options.solver, [&] { return Calibrate(samples, points, rig, &board, options); });
  py::dict dict = YamlTextToDict(CalibrateResultYaml(result, options));
  dict["se3_spline"] = py::cast(result.MakeSpline());
  return dict;
}

}  // namespace

void BindCalibrate(py::module_& m) {
  m.def("calibrate",
        &CalibrateFunction,
        py::arg("imu"),
        py::arg("observations"),
        py::arg("camchain"),
        py::arg("target"),
        py::kw_only(),
        py::arg("imu_yaml") = py::none(),
        py::arg("imu_noise") = "estimated",
        py::arg("rolling_shutter") = false,
        py::arg("estimate_intrinsics") = false,
        py::arg("no_time_offset") = false,
        py::arg("knot_spacing") = 0.05,
        py::arg("trajectory") = "se3",
        py::arg("pixel_sigma") = 0.0,
        py::arg("huber") = 2.0,
        py::arg("min_corners") = 8,
        py::arg("gravity") = 9.81,
        py::arg("accel_unit") = "m/s^2",
        py::arg("gyro_unit") = "rad/s",
        py::arg("threads") = 1,
        R"(Camera-IMU calibration as `splinecal calibrate`, with its flags as keywords. imu: a
EuRoC imu0/data.csv path or {t_ns, gyro, accel}; observations: an observations.csv path or
{t_ns, cam_id, point_id, uv}; camchain and target: Kalibr YAML paths. Returns result.yaml's
keys plus se3_spline (SE3Spline). Ctrl-C stops the solve (KeyboardInterrupt).)");
}

}  // namespace python
}  // namespace splinecal
