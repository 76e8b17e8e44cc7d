// splinecal.correct: `splinecal correct` (report/correct_report.h) with every flag as a keyword,
// returning its result.yaml as a dict plus the corrected readings.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>
#include <string>
#include <vector>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "numpy_io.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/report/correct_report.h"

namespace splinecal {
namespace python {

namespace {

py::dict CorrectFunction(py::handle imu,
                         py::handle imu_intrinsics,
                         int imu_index,
                         py::handle gyro_bias,
                         py::handle accel_bias,
                         int derivative_window,
                         const std::string& accel_unit,
                         const std::string& gyro_unit,
                         py::handle out) {
  ImuCorrectionOptions options;
  options.gyro_bias = Vector3Argument(gyro_bias, "gyro_bias");
  options.accel_bias = Vector3Argument(accel_bias, "accel_bias");
  if (derivative_window < 1 || derivative_window > 1000) {
    throw py::value_error("derivative_window: expected 1 to 1000 samples, got " +
                          std::to_string(derivative_window));
  }
  options.derivative_half_window = derivative_window;
  const std::string intrinsics_path = PathArgument(imu_intrinsics, "imu_intrinsics");
  const std::vector<ImuCalibration> imus = ReadImuModelsYaml(intrinsics_path);
  if (imu_index < 0 || imu_index >= static_cast<int>(imus.size())) {
    throw py::value_error("imu_index: the file has " + std::to_string(imus.size()) +
                          " IMU(s), got " + std::to_string(imu_index));
  }
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  const std::vector<ImuSample> raw = ImuInUnits(imu, accel_unit, gyro_unit);
  const CorrectRun run = RunCorrection(
      imus[imu_index], raw, options, {AsPath(imu).value_or(""), intrinsics_path, imu_index});
  py::dict result = FinishOutputs(output.get(), run.files);
  py::dict corrected;
  corrected["t_ns"] = TimeColumn(run.corrected);
  corrected["gyro"] = Vector3Column(run.corrected, [](const auto& s) { return s.gyro; });
  corrected["accel"] = Vector3Column(run.corrected, [](const auto& s) { return s.accel; });
  result["imu"] = corrected;
  return result;
}

}  // namespace

void BindCorrect(py::module_& m) {
  DefCommand(
      m,
      "correct",
      &CorrectFunction,
      R"(`splinecal correct` with its flags as keywords: the IMU model of imu_intrinsics (Kalibr's
imu-*.yaml path; imu_index picks imuN) inverted on every raw reading of imu (a EuRoC
imu0/data.csv path or {t_ns, gyro, accel}); the constant gyro_bias, accel_bias subtracted; the
size effect's angular acceleration the slope of the corrected gyro over 2 derivative_window + 1
samples (docs/imu_models.md). out: a folder to write mav0/imu0/data.csv and result.yaml to.
Returns result.yaml's keys plus imu {t_ns, gyro, accel}: the angular velocity and specific force
of an ideal IMU at the IMU's origin, in its accelerometer frame.)",
      py::arg("imu"),
      py::arg("imu_intrinsics"),
      py::kw_only(),
      py::arg("imu_index") = 0,
      py::arg("gyro_bias") = std::vector<double>{0.0, 0.0, 0.0},
      py::arg("accel_bias") = std::vector<double>{0.0, 0.0, 0.0},
      py::arg("derivative_window") = ImuCorrectionOptions{}.derivative_half_window,
      py::arg("accel_unit") = "m/s^2",
      py::arg("gyro_unit") = "rad/s");
}

}  // namespace python
}  // namespace splinecal
