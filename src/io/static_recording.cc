#include "splinecal/io/static_recording.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string_view>
#include <utility>
#include <vector>

#include "row_checks.h"
#include "splinecal/axis_name.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/parallel_euroc_imu.h"
#include "splinecal/io/text_file.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// After this many rows the average row length is known well enough to reserve memory for the
// whole file at once (instead of letting the vectors double, which would briefly need 1.5-2x).
constexpr int64_t kRowsForEstimate = 1024;
// A mean accelerometer reading with a magnitude in this range is gravity in units of g.
constexpr double kGravityInGLow = 0.5;
constexpr double kGravityInGHigh = 1.5;

// Reserves every axis for the whole file, estimated from the rows read so far.
class CapacityPlanner {
 public:
  explicit CapacityPlanner(const std::string& path) {
    std::error_code error;
    file_bytes_ = static_cast<int64_t>(std::filesystem::file_size(path, error));
    if (error) file_bytes_ = 0;
  }
  void AddRow(std::string_view line, std::vector<AxisSeries>* axes) {
    if (rows_ >= kRowsForEstimate) return;
    bytes_ += static_cast<int64_t>(line.size()) + 1;
    if (++rows_ < kRowsForEstimate || file_bytes_ == 0) return;
    const int64_t estimate = file_bytes_ / std::max<int64_t>(1, bytes_ / rows_) * 21 / 20 + 16;
    for (AxisSeries& axis : *axes) axis.samples.reserve(static_cast<size_t>(estimate));
  }

 private:
  int64_t file_bytes_ = 0;
  int64_t bytes_ = 0;
  int64_t rows_ = 0;
};

std::vector<AxisSeries> MakeAxes(bool gyro, bool accel, int count_per_sensor) {
  std::vector<AxisSeries> axes;
  for (int s = 0; s < 2; ++s) {
    if ((s == 0 && !gyro) || (s == 1 && !accel)) continue;
    for (int a = 0; a < count_per_sensor; ++a) {
      AxisSeries axis;
      axis.sensor = s == 0 ? ImuSensor::kGyroscope : ImuSensor::kAccelerometer;
      axis.axis = a;
      axes.push_back(std::move(axis));
    }
  }
  return axes;
}

// Field names for error messages ("gyro x"), built once.
std::vector<std::string> FieldNames(const std::vector<AxisSeries>& axes) {
  std::vector<std::string> names;
  for (const AxisSeries& axis : axes) {
    names.push_back(std::string(axis.sensor == ImuSensor::kGyroscope ? "gyro " : "accel ") +
                    AxisName(axis.axis));
  }
  return names;
}

double ScaleOf(const AxisSeries& axis, const StaticReadOptions& options) {
  return axis.sensor == ImuSensor::kGyroscope ? options.gyro_scale : options.accel_scale;
}

// One reading in the file's unit, scaled; refused beyond the input layer's plausibility limits
// (io/text_file.h), like every other IMU reader.
double ParseReading(std::string_view field,
                    const TextFileReader& reader,
                    const std::string& name,
                    const AxisSeries& axis,
                    const StaticReadOptions& options) {
  const double scale = ScaleOf(axis, options);
  const bool gyro = axis.sensor == ImuSensor::kGyroscope;
  const double limit = (gyro ? kMaxAngularRate : kMaxAcceleration) / scale;
  return scale * ParseBoundedDouble(field, reader, name, limit, gyro ? "rad/s" : "m/s^2");
}

void CheckScales(const StaticReadOptions& options) {
  if (!(std::isfinite(options.gyro_scale) && options.gyro_scale > 0.0)) {
    throw Error("gyro scale must be positive and finite, got " +
                std::to_string(options.gyro_scale));
  }
  if (!(std::isfinite(options.accel_scale) && options.accel_scale > 0.0)) {
    throw Error("accel scale must be positive and finite, got " +
                std::to_string(options.accel_scale));
  }
}

// Refuses accelerometer data in g: the mean reading of a static IMU is gravity, 9.81 m/s^2.
void CheckAccelUnits(const std::string& path,
                     const std::vector<AxisSeries>& axes,
                     const StaticReadOptions& options) {
  if (!options.check_accel_units || options.accel_scale != 1.0) return;
  double squared = 0.0;
  int count = 0;
  for (const AxisSeries& axis : axes) {
    if (axis.sensor != ImuSensor::kAccelerometer || axis.samples.empty()) continue;
    // Four interleaved double sums: enough for a test against 0.5 g and 1.5 g, and vectorised
    // (a long double sum of 3 x 10^7 readings took 58 ms, all on one thread before the analysis).
    double sums[4] = {0.0, 0.0, 0.0, 0.0};
    const size_t n = axis.samples.size();
    const double* y = axis.samples.data();
    size_t i = 0;
    for (; i + 4 <= n; i += 4) {
      for (int lane = 0; lane < 4; ++lane) sums[lane] += y[i + lane];
    }
    for (; i < n; ++i) sums[0] += y[i];
    const double mean = ((sums[0] + sums[1]) + (sums[2] + sums[3])) / static_cast<double>(n);
    squared += mean * mean;
    ++count;
  }
  const double magnitude = std::sqrt(squared);
  if (count == 3 && magnitude > kGravityInGLow && magnitude < kGravityInGHigh) {
    throw Error(path,
                0,
                StringPrintf("mean accelerometer reading has magnitude %.3f: the data looks like "
                             "units of g, expected m/s^2 (pass --accel-scale 9.80665)",
                             magnitude));
  }
}

// The rate plain columns are read at (they carry no timestamps).
void CheckColumnRate(double rate_hz) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw Error("the sample rate of plain columns must be positive and finite, got " +
                std::to_string(rate_hz) + " Hz (--rate)");
  }
  CheckImuRate(rate_hz, "--rate", /*from_timestamps=*/false);
}

void CheckEnoughRows(const std::string& path, const std::vector<AxisSeries>& axes) {
  const size_t rows = axes.empty() ? 0 : axes.front().samples.size();
  if (rows < 2) throw Error(path, 0, "needs at least 2 data rows, found " + std::to_string(rows));
}

// The parallel path (io/parallel_euroc_imu.h) for a file of at least parallel_min_bytes; nullopt
// when it is smaller or anything in it needs the TextFileReader path, a gap included (that path
// names its line).
std::optional<StaticRecording> ReadEurocInParallel(const std::string& path,
                                                   const StaticReadOptions& options) {
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (error || static_cast<int64_t>(bytes) < options.parallel_min_bytes) return std::nullopt;
  std::optional<internal::EurocImuColumns> columns =
      internal::ReadEurocImuParallel(path, options.gyro_scale, options.accel_scale);
  if (!columns.has_value()) return std::nullopt;
  const int64_t rows = static_cast<int64_t>(columns->values[0].size());
  const double mean_period_s =
      1e-9 * static_cast<double>(columns->last_t_ns - columns->first_t_ns) / (rows - 1);
  if (1e-9 * columns->largest_step_ns > options.max_gap_periods * mean_period_s) {
    return std::nullopt;
  }
  StaticRecording recording;
  recording.source = path;
  recording.rate_hz = 1.0 / mean_period_s;
  recording.axes = MakeAxes(true, true, 3);
  for (int a = 0; a < 6; ++a) recording.axes[a].samples = std::move(columns->values[a]);
  CheckAccelUnits(path, recording.axes, options);
  CheckImuRate(recording.rate_hz, path);
  return recording;
}

}  // namespace

StaticRecording ReadEurocStaticRecording(const std::string& path,
                                         const StaticReadOptions& options) {
  CheckScales(options);
  if (std::optional<StaticRecording> fast = ReadEurocInParallel(path, options)) {
    return std::move(*fast);
  }
  TextFileReader reader(path);
  StaticRecording recording;
  recording.source = path;
  recording.axes = MakeAxes(true, true, 3);
  const std::vector<std::string> names = FieldNames(recording.axes);
  const std::string timestamp_name = "timestamp";
  CapacityPlanner planner(path);
  std::vector<std::string_view> fields;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t rows = 0;
  int64_t largest_step_ns = 0;
  int64_t largest_step_line = 0;
  while (reader.NextLine()) {
    SplitFields(reader.line(), &fields);
    if (internal::IsHeaderRow(reader, fields)) continue;
    internal::CheckColumnCount(reader, fields, 7, "EuRoC IMU (t_ns, gyro xyz, accel xyz)");
    const int64_t t_ns = ParseTimestampNs(fields[0], reader, timestamp_name);
    if (rows > 0) {
      if (t_ns <= last_t_ns) internal::FailNotIncreasing(reader, last_t_ns, t_ns, fields[0]);
      if (t_ns - last_t_ns > largest_step_ns) {
        largest_step_ns = t_ns - last_t_ns;
        largest_step_line = reader.line_number();
      }
    } else {
      first_t_ns = t_ns;
    }
    last_t_ns = t_ns;
    for (size_t a = 0; a < 6; ++a) {
      recording.axes[a].samples.push_back(
          ParseReading(fields[1 + a], reader, names[a], recording.axes[a], options));
    }
    ++rows;
    planner.AddRow(reader.line(), &recording.axes);
  }
  CheckEnoughRows(path, recording.axes);
  const double mean_period_s = 1e-9 * static_cast<double>(last_t_ns - first_t_ns) / (rows - 1);
  recording.rate_hz = 1.0 / mean_period_s;
  if (1e-9 * largest_step_ns > options.max_gap_periods * mean_period_s) {
    throw Error(path,
                largest_step_line,
                StringPrintf("gap of %.6g s before this row, more than %g mean sample periods "
                             "(%.6g s): the Allan variance needs uniformly sampled data (cut the "
                             "file at the gap)",
                             1e-9 * largest_step_ns,
                             options.max_gap_periods,
                             mean_period_s));
  }
  CheckAccelUnits(path, recording.axes, options);
  CheckImuRate(recording.rate_hz, path);
  return recording;
}

StaticRecording ReadBagStaticRecording(const BagImuSource& source,
                                       const StaticReadOptions& options) {
  CheckScales(options);
  BagImuStream stream(source, options);
  const std::string name = source.Name();
  StaticRecording recording;
  recording.source = name;
  recording.axes = MakeAxes(true, true, 3);
  const BagReader& bag = stream.bag();
  const auto count = bag.topics()[bag.FindTopic(source.topic)].message_count;
  for (AxisSeries& axis : recording.axes) axis.samples.reserve(static_cast<size_t>(count));
  ImuSample sample;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  int64_t largest_step_message = 0;
  int64_t largest_step_t_ns = 0;
  while (stream.Next(&sample)) {
    if (stream.count() == 1) {
      first_t_ns = sample.t_ns;
    } else if (sample.t_ns - last_t_ns > largest_step_ns) {
      largest_step_ns = sample.t_ns - last_t_ns;
      largest_step_message = stream.count();
      largest_step_t_ns = sample.t_ns;
    }
    last_t_ns = sample.t_ns;
    for (int a = 0; a < 3; ++a) {
      recording.axes[a].samples.push_back(sample.gyro[a]);
      recording.axes[3 + a].samples.push_back(sample.accel[a]);
    }
  }
  CheckEnoughRows(name, recording.axes);
  const int64_t rows = stream.count();
  const double mean_period_s = 1e-9 * static_cast<double>(last_t_ns - first_t_ns) / (rows - 1);
  recording.rate_hz = 1.0 / mean_period_s;
  if (1e-9 * largest_step_ns > options.max_gap_periods * mean_period_s) {
    throw Error(StringPrintf("%s: gap of %.6g s before message %lld (t = %lld ns), more than %g "
                             "mean sample periods (%.6g s): the Allan variance needs uniformly "
                             "sampled data",
                             name.c_str(), 1e-9 * largest_step_ns,
                             static_cast<long long>(largest_step_message),
                             static_cast<long long>(largest_step_t_ns), options.max_gap_periods,
                             mean_period_s));
  }
  CheckAccelUnits(name, recording.axes, options);
  CheckImuRate(recording.rate_hz, name);
  return recording;
}

StaticRecording ReadColumnStaticRecording(const std::string& path,
                                          double rate_hz,
                                          std::optional<ImuSensor> sensor,
                                          const StaticReadOptions& options) {
  CheckScales(options);
  CheckColumnRate(rate_hz);
  TextFileReader reader(path);
  StaticRecording recording;
  recording.source = path;
  recording.rate_hz = rate_hz;
  CapacityPlanner planner(path);
  std::vector<std::string_view> fields;
  std::vector<std::string> names;
  size_t columns = 0;
  while (reader.NextLine()) {
    SplitFields(reader.line(), &fields);
    if (internal::IsHeaderRow(reader, fields)) continue;
    if (columns == 0) {
      // The first data row fixes the layout.
      columns = fields.size();
      if (columns == 6) {
        if (sensor.has_value()) {
          reader.Fail(
              "6 columns are gyro xyz then accel xyz; --sensor is for 1 to 3 columns of "
              "one sensor");
        }
        recording.axes = MakeAxes(true, true, 3);
      } else if (columns >= 1 && columns <= 3) {
        if (!sensor.has_value()) {
          reader.Fail(std::to_string(columns) +
                      " column(s) of one sensor: say which with --sensor gyro or --sensor accel");
        }
        recording.axes = MakeAxes(*sensor == ImuSensor::kGyroscope,
                                  *sensor == ImuSensor::kAccelerometer,
                                  static_cast<int>(columns));
      } else {
        reader.Fail("expected 1, 2, 3 (one sensor) or 6 (gyro xyz, accel xyz) columns, found " +
                    std::to_string(columns));
      }
      names = FieldNames(recording.axes);
    }
    internal::CheckColumnCount(
        reader, fields, columns, columns == 6 ? "gyro xyz, accel xyz" : "one sensor's axes");
    for (size_t a = 0; a < columns; ++a) {
      recording.axes[a].samples.push_back(
          ParseReading(fields[a], reader, names[a], recording.axes[a], options));
    }
    planner.AddRow(reader.line(), &recording.axes);
  }
  CheckEnoughRows(path, recording.axes);
  CheckAccelUnits(path, recording.axes, options);
  return recording;
}

StaticRecording StaticRecordingFromColumns(const std::vector<std::vector<double>>& columns,
                                           double rate_hz,
                                           std::optional<ImuSensor> sensor,
                                           const std::string& source,
                                           const StaticReadOptions& options) {
  CheckScales(options);
  CheckColumnRate(rate_hz);
  StaticRecording recording;
  recording.source = source;
  recording.rate_hz = rate_hz;
  if (columns.size() == 6) {
    if (sensor.has_value()) {
      throw Error(source + ": 6 columns are gyro xyz then accel xyz; a sensor is for 1 to 3 "
                           "columns of one sensor");
    }
    recording.axes = MakeAxes(true, true, 3);
  } else if (columns.size() >= 1 && columns.size() <= 3) {
    if (!sensor.has_value()) {
      throw Error(source + ": " + std::to_string(columns.size()) +
                  " column(s) of one sensor: say which sensor, gyro or accel");
    }
    recording.axes = MakeAxes(*sensor == ImuSensor::kGyroscope,
                              *sensor == ImuSensor::kAccelerometer,
                              static_cast<int>(columns.size()));
  } else {
    throw Error(source + ": expected 1, 2, 3 (one sensor) or 6 (gyro xyz, accel xyz) columns, "
                         "found " + std::to_string(columns.size()));
  }
  const std::vector<std::string> names = FieldNames(recording.axes);
  for (size_t a = 0; a < columns.size(); ++a) {
    AxisSeries& axis = recording.axes[a];
    const double scale = ScaleOf(axis, options);
    const bool gyro = axis.sensor == ImuSensor::kGyroscope;
    const double limit = gyro ? kMaxAngularRate : kMaxAcceleration;  // after scaling
    axis.samples.reserve(columns[a].size());
    for (size_t i = 0; i < columns[a].size(); ++i) {
      const double value = scale * columns[a][i];
      if (!(std::abs(value) <= limit)) {
        throw Error(StringPrintf("%s: %s at row %zu is %g %s, beyond the plausible %g",
                                 source.c_str(),
                                 names[a].c_str(),
                                 i,
                                 value,
                                 gyro ? "rad/s" : "m/s^2",
                                 limit));
      }
      axis.samples.push_back(value);
    }
  }
  CheckEnoughRows(source, recording.axes);
  CheckAccelUnits(source, recording.axes, options);
  return recording;
}

}  // namespace splinecal
