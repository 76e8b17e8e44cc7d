// splinecal.integrate: `splinecal integrate` (report/integrate_report.h) with every flag as a
// keyword, returning its result.yaml as a dict.
#include <pybind11/pybind11.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/report/integrate_report.h"

namespace splinecal {
namespace python {

namespace {

// As the command bounds --start and --duration: int64 nanoseconds cannot overflow.
double SpanArgument(double seconds, const std::string& name) {
  NonNegativeArgument(seconds, name);
  if (seconds > 1e9) {
    throw py::value_error(name + ": at most 1e9 s, got " + std::to_string(seconds));
  }
  return seconds;
}

py::dict IntegrateFunction(py::handle imu,
                           py::handle groundtruth,
                           py::handle method,
                           double start,
                           double duration,
                           double gravity,
                           const std::string& accel_unit,
                           const std::string& gyro_unit,
                           py::handle out,
                           py::handle bag,
                           const std::string& imu_topic,
                           const std::string& bag_time) {
  const std::vector<IntegrationMethod> methods =
      ParseIntegrationMethods(CommaListArgument(method, "method"));
  PositiveArgument(gravity, "gravity");
  SpanArgument(start, "start");
  SpanArgument(duration, "duration");
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  const BagImuArguments bag_arguments{bag, imu_topic, bag_time};
  RequiredArgument(groundtruth, "groundtruth");
  const std::vector<ImuSample> samples = ImuInUnits(imu, bag_arguments, accel_unit, gyro_unit);
  const std::vector<GroundTruthState> truth = GroundTruthStates(groundtruth, "groundtruth");
  const IntegrationSpan span = ChooseIntegrationSpan(samples,
                                                     truth,
                                                     start,
                                                     duration,
                                                     ImuSourceName(imu, bag_arguments, "imu"),
                                                     AsPath(groundtruth).value_or("groundtruth"));
  const IntegrationRun run =
      RunWithoutGil([&] { return RunIntegration(samples, truth, span, methods, gravity); });
  return FinishOutputs(output.get(), run.files);
}

}  // namespace

void BindIntegrate(py::module_& m) {
  DefImuCommand(
      m,
      "integrate",
      &IntegrateFunction,
      R"(IMU dead reckoning as `splinecal integrate`, with its flags as keywords. imu: a EuRoC
imu0/data.csv path or {t_ns, gyro, accel}; groundtruth: a EuRoC state_groundtruth_estimate0
path or {t_ns, T_w_s, v_w, gyro_bias, accel_bias} (simulate's ground_truth); method: "euler,rk4"
or ["euler", "rk4"]; start, duration [s] (duration 0: to the end of the data). out: a folder to
write result.yaml, trajectory_<method>.csv and trajectory.svg to. Returns result.yaml's keys:
per method final_position_error_m, final_rotation_error_deg, ate_rmse_m.)",
      py::arg("imu") = py::none(),
      py::arg("groundtruth") = py::none(),
      py::kw_only(),
      py::arg("method") = "euler,midpoint,rk4",
      py::arg("start") = 0.0,
      py::arg("duration") = 0.0,
      py::arg("gravity") = kDefaultGravity,
      py::arg("accel_unit") = "m/s^2",
      py::arg("gyro_unit") = "rad/s");
}

}  // namespace python
}  // namespace splinecal
