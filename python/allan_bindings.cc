// splinecal.allan_deviation (allan/allan_deviation.h) and splinecal.allan, the noise
// identification of `splinecal allan` (allan/allan.h) returning its result.yaml as a dict.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>

#include "bindings.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/allan/allan.h"
#include "splinecal/allan/allan_deviation.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/static_recording.h"
#include "yaml_to_python.h"

namespace splinecal {
namespace python {

namespace {

py::tuple AllanDeviation(py::handle x_object,
                         double rate_hz,
                         int taus_per_decade,
                         double max_tau_fraction) {
  PositiveArgument(rate_hz, "rate_hz");
  const py::array x_any = py::array::ensure(x_object);
  const bool one_column = x_any && x_any.ndim() == 1;
  const py::array_t<double> x = DoubleArray(
      x_object, "x", one_column ? std::vector<py::ssize_t>{-1} : std::vector<py::ssize_t>{-1, -1});
  const py::ssize_t n = x.shape(0);
  const py::ssize_t k = one_column ? 1 : x.shape(1);
  const std::vector<int64_t> cluster_sizes =
      AllanClusterSizes(n, taus_per_decade, max_tau_fraction);
  std::vector<std::vector<double>> columns(k, std::vector<double>(n));
  for (py::ssize_t i = 0; i < n; ++i) {
    for (py::ssize_t j = 0; j < k; ++j) columns[j][i] = x.data()[i * k + j];
  }
  std::vector<AllanCurve> curves = RunWithoutGil([&] {
    std::vector<AllanCurve> result;
    for (py::ssize_t j = 0; j < k; ++j) {
      result.push_back(OverlappingAllanDeviation(
          columns[j], rate_hz, cluster_sizes, "x[:, " + std::to_string(j) + "]"));
    }
    return result;
  });
  const auto m = static_cast<py::ssize_t>(cluster_sizes.size());
  py::array_t<double> tau(m);
  std::copy(curves[0].tau_s.begin(), curves[0].tau_s.end(), tau.mutable_data());
  py::array_t<double> adev = one_column ? py::array_t<double>(m) : py::array_t<double>({m, k});
  for (py::ssize_t i = 0; i < m; ++i) {
    for (py::ssize_t j = 0; j < k; ++j) adev.mutable_data()[i * k + j] = curves[j].adev[i];
  }
  return py::make_tuple(tau, adev);
}

// Gyro xyz [rad/s] then accel xyz [m/s^2] at rate_hz, as `splinecal allan --columns` reads them.
StaticRecording RecordingFromArray(py::handle imu,
                                   double rate_hz,
                                   double gyro_scale,
                                   double accel_scale) {
  const py::array_t<double> samples = DoubleArray(imu, "imu", {-1, 6});
  StaticRecording recording;
  recording.source = "numpy array";  // result.yaml's `source`, the input's name
  recording.rate_hz = PositiveArgument(rate_hz, "rate_hz");
  CheckImuRate(recording.rate_hz, "rate_hz", /*from_timestamps=*/false);
  for (int column = 0; column < 6; ++column) {
    AxisSeries axis;
    axis.sensor = column < 3 ? ImuSensor::kGyroscope : ImuSensor::kAccelerometer;
    axis.axis = column % 3;
    const double scale = column < 3 ? gyro_scale : accel_scale;
    axis.samples.resize(samples.shape(0));
    for (py::ssize_t i = 0; i < samples.shape(0); ++i) {
      axis.samples[i] = scale * samples.data()[i * 6 + column];
    }
    recording.axes.push_back(std::move(axis));
  }
  return recording;
}

py::dict Allan(py::handle imu,
               py::object rate_hz,
               int taus_per_decade,
               double max_tau_fraction,
               int max_passes,
               const std::string& combine,
               double start,
               py::object end,
               bool allow_motion,
               double gyro_scale,
               double accel_scale) {
  AllanOptions options;
  options.taus_per_decade = taus_per_decade;
  options.max_tau_fraction = max_tau_fraction;
  if (max_passes < 0) throw py::value_error("max_passes: expected 0 (no budget) or positive");
  options.max_passes = max_passes;
  if (combine == "mean") {
    options.combine = CombineAxes::kMean;
  } else if (combine == "max") {
    options.combine = CombineAxes::kMax;
  } else {
    throw py::value_error("combine: expected mean or max, got '" + combine + "'");
  }
  options.start_s = start;
  if (!end.is_none()) options.end_s = end.cast<double>();
  if (!(options.start_s >= 0.0) || !(options.end_s > options.start_s)) {
    throw py::value_error("start, end: expected 0 <= start < end (seconds)");
  }
  options.motion_policy = allow_motion ? MotionPolicy::kMarkUnreliable : MotionPolicy::kRefuse;
  PositiveArgument(gyro_scale, "gyro_scale");
  PositiveArgument(accel_scale, "accel_scale");
  StaticRecording recording;
  if (const std::optional<std::string> path = AsPath(imu)) {
    if (!rate_hz.is_none()) {
      throw py::value_error("rate_hz: is for arrays; EuRoC files carry timestamps");
    }
    StaticReadOptions read;
    read.gyro_scale = gyro_scale;
    read.accel_scale = accel_scale;
    recording = RunWithoutGil([&] { return ReadEurocStaticRecording(*path, read); });
  } else {
    if (rate_hz.is_none()) throw py::value_error("rate_hz: required with an array");
    recording = RecordingFromArray(imu, rate_hz.cast<double>(), gyro_scale, accel_scale);
  }
  const std::string yaml = RunWithoutGil(
      [&] { return AllanResultYamlText(ComputeAllan(std::move(recording), options)); });
  return YamlTextToDict(yaml);
}

}  // namespace

void BindAllan(py::module_& m) {
  m.def("allan_deviation",
        &AllanDeviation,
        py::arg("x"),
        py::arg("rate_hz"),
        py::arg("taus_per_decade") = 10,
        py::arg("max_tau_fraction") = 0.1,
        R"((tau (m,) [s], adev (m, k)): the overlapping Allan deviation of each column of x (n, k)
(or (n,) -> adev (m,)) sampled at rate_hz, at the log-spaced averaging times of
`splinecal allan` (taus_per_decade per decade, up to max_tau_fraction of the record), fully
overlapping at every one (no work budget).)");
  m.def("allan",
        &Allan,
        py::arg("imu"),
        py::arg("rate_hz") = py::none(),
        py::kw_only(),
        py::arg("taus_per_decade") = 10,
        py::arg("max_tau_fraction") = 0.1,
        py::arg("max_passes") = kDefaultAllanMaxPasses,
        py::arg("combine") = "mean",
        py::arg("start") = 0.0,
        py::arg("end") = py::none(),
        py::arg("allow_motion") = false,
        py::arg("gyro_scale") = 1.0,
        py::arg("accel_scale") = 1.0,
        R"(IMU noise from a static recording, as `splinecal allan`: imu is an array (n, 6) of
gyro xyz [rad/s] and accel xyz [m/s^2] at rate_hz, or the path of a EuRoC imu0/data.csv.
max_passes is the work budget of `--max-passes` (0: always fully overlapping). Returns
result.yaml's content as a dict (Kalibr densities, every term per axis).)");
}

}  // namespace python
}  // namespace splinecal
