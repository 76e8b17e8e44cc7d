// splinecal.allan_deviation (allan/allan_deviation.h) and splinecal.allan, the noise
// identification of `splinecal allan` (allan/allan.h) returning its result.yaml as a dict.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <vector>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/allan/allan.h"
#include "splinecal/allan/allan_deviation.h"
#include "splinecal/error.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/static_recording.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/report/option_names.h"

namespace splinecal {
namespace python {

namespace {

// The columns of an array `name` (n, k) or (n,) (DoubleArray's checks): x of allan_deviation, or
// imu of allan: 6 (gyro xyz, accel xyz) or 1 to 3 of one sensor, as `splinecal allan --columns`
// reads a file's (io/static_recording.h checks them).
struct ArrayColumns {
  ArrayColumns(py::handle array, const std::string& name) {
    const py::array any = py::array::ensure(array);
    one_column = any && any.ndim() == 1;
    const py::array_t<double> x = DoubleArray(
        array, name, one_column ? std::vector<py::ssize_t>{-1} : std::vector<py::ssize_t>{-1, -1});
    rows = x.shape(0);
    const py::ssize_t k = one_column ? 1 : x.shape(1);
    columns.assign(k, std::vector<double>(rows));
    for (py::ssize_t i = 0; i < rows; ++i) {
      for (py::ssize_t j = 0; j < k; ++j) columns[j][i] = x.data()[i * k + j];
    }
  }

  bool one_column;  // a 1-d array
  py::ssize_t rows;
  std::vector<std::vector<double>> columns;
};

py::tuple AllanDeviation(py::handle x_object,
                         double rate_hz,
                         int taus_per_decade,
                         double max_tau_fraction) {
  PositiveArgument(rate_hz, "rate_hz");
  const ArrayColumns x(x_object, "x");
  const bool one_column = x.one_column;
  const std::vector<std::vector<double>>& columns = x.columns;
  const auto k = static_cast<py::ssize_t>(columns.size());
  const std::vector<int64_t> cluster_sizes =
      AllanClusterSizes(x.rows, taus_per_decade, max_tau_fraction);
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

std::optional<ImuSensor> SensorArgument(py::handle sensor) {
  if (sensor.is_none()) return std::nullopt;
  const std::string name = py::str(sensor);
  if (name == "gyro") return ImuSensor::kGyroscope;
  if (name == "accel") return ImuSensor::kAccelerometer;
  throw py::value_error("sensor: expected gyro or accel, got '" + name + "'");
}

py::dict Allan(py::handle imu,
               py::handle rate,
               py::handle columns,
               py::handle sensor,
               int taus_per_decade,
               double max_tau_fraction,
               int max_passes,
               const std::string& combine,
               double start,
               double end,
               bool allow_motion,
               double gyro_scale,
               double accel_scale,
               const std::string& gyro_unit,
               const std::string& accel_unit,
               py::handle out,
               py::handle bag,
               const std::string& imu_topic,
               const std::string& bag_time) {
  if (int{!imu.is_none()} + int{!columns.is_none()} + int{!bag.is_none()} != 1) {
    throw py::value_error(
        "imu, bag, columns: give the static recording as imu (a EuRoC imu0/data.csv path or an "
        "array), as bag (a recording) with imu_topic, or as columns (a plain-columns path) with "
        "rate: exactly one");
  }
  AllanOptions options;
  options.taus_per_decade = taus_per_decade;
  options.max_tau_fraction = max_tau_fraction;
  if (max_passes < 0) throw py::value_error("max_passes: expected 0 (no budget) or positive");
  options.max_passes = max_passes;
  if (!ValueNamed(kCombineAxesNames, combine, &options.combine)) {
    throw py::value_error("combine: expected " + JoinNames(kCombineAxesNames, " or ") +
                          ", got '" + combine + "'");
  }
  options.start_s = start;
  if (end != 0.0) options.end_s = end;  // 0: the end, as --end
  if (!(options.start_s >= 0.0) || !(options.end_s > options.start_s)) {
    throw py::value_error("start, end: expected 0 <= start < end (seconds)");
  }
  options.motion_policy = allow_motion ? MotionPolicy::kMarkUnreliable : MotionPolicy::kRefuse;
  AllanClusterSizes(1, options.taus_per_decade, options.max_tau_fraction);
  // The units as the command combines them: --gyro-unit / --accel-unit times the scales.
  const ImuReadOptions units = ImuUnitReadOptions(accel_unit, gyro_unit);
  StaticReadOptions read;
  read.gyro_scale = units.gyro_scale * PositiveArgument(gyro_scale, "gyro_scale");
  read.accel_scale = units.accel_scale * PositiveArgument(accel_scale, "accel_scale");
  read.check_accel_units = units.check_accel_units;
  const std::optional<ImuSensor> axes_of = SensorArgument(sensor);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);

  StaticRecording recording;
  if (!bag.is_none()) {
    if (!rate.is_none() || axes_of) {
      throw py::value_error("rate, sensor: are for arrays and columns; bags carry timestamps");
    }
    BagImuSource source;
    source.paths = BagPaths(bag);
    source.topic = imu_topic;
    source.time = ParseBagTime(bag_time);
    recording = RunWithoutGil([&] { return ReadBagStaticRecording(source, read); });
  } else if (const std::optional<std::string> path = AsPath(imu)) {
    if (!rate.is_none() || axes_of) {
      throw py::value_error("rate, sensor: are for arrays and columns; EuRoC files carry "
                            "timestamps");
    }
    recording = RunWithoutGil([&] { return ReadEurocStaticRecording(*path, read); });
  } else if (!columns.is_none()) {
    if (rate.is_none()) throw py::value_error("rate: required with columns");
    const double rate_hz = PositiveArgument(rate.cast<double>(), "rate");
    const std::string path = PathArgument(columns, "columns");
    recording = RunWithoutGil(
        [&] { return ReadColumnStaticRecording(path, rate_hz, axes_of, read); });
  } else {
    if (rate.is_none()) throw py::value_error("rate: required with an array");
    const double rate_hz = PositiveArgument(rate.cast<double>(), "rate");
    const std::vector<std::vector<double>> values = ArrayColumns(imu, "imu").columns;
    // Errors name the argument; result.yaml's `source` says what it was.
    recording = StaticRecordingFromColumns(values, rate_hz, axes_of, "imu", read);
    recording.source = "numpy array";
  }
  const std::vector<OutputFile> files = RunWithoutGil(
      [&] { return AllanOutputFiles(ComputeAllan(std::move(recording), options)); });
  return FinishOutputs(output.get(), files);
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
  const AllanOptions defaults;
  DefImuCommand(
      m,
      "allan",
      &Allan,
      R"(IMU noise from a static recording, as `splinecal allan` with its flags as keywords.
imu: the path of a EuRoC imu0/data.csv, or an array (n, 6) of gyro xyz [rad/s] and accel xyz
[m/s^2] (or (n, 1..3) of one sensor, with sensor="gyro" or "accel") sampled at rate [Hz];
columns: the path of a plain-columns file at rate (instead of imu). Arrays are checked as the
command checks a file: an accelerometer in g is refused (accel_unit="g" or accel_scale=9.80665
reads it). max_passes is the work budget (0: always fully overlapping); end 0: the end. out: a
folder to write allan.csv, imu.yaml, result.yaml and allan.svg to. Returns result.yaml's content
as a dict (Kalibr densities, every term per axis).)",
      py::arg("imu") = py::none(),
      py::arg("rate") = py::none(),
      py::kw_only(),
      py::arg("columns") = py::none(),
      py::arg("sensor") = py::none(),
      py::arg("taus_per_decade") = defaults.taus_per_decade,
      py::arg("max_tau_fraction") = defaults.max_tau_fraction,
      py::arg("max_passes") = defaults.max_passes,
      py::arg("combine") = "mean",
      py::arg("start") = defaults.start_s,
      py::arg("end") = 0.0,
      py::arg("allow_motion") = false,
      py::arg("gyro_scale") = 1.0,
      py::arg("accel_scale") = 1.0,
      py::arg("gyro_unit") = "rad/s",
      py::arg("accel_unit") = "m/s^2");
}

}  // namespace python
}  // namespace splinecal
