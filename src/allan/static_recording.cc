#include "splinecal/allan/static_recording.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <string_view>
#include <thread>

#include "splinecal/error.h"
#include "splinecal/io/row_checks.h"
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

const char* const kAxisLetters[] = {"x", "y", "z"};

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
                    kAxisLetters[axis.axis]);
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
    long double sum = 0.0L;
    for (const double v : axis.samples) sum += v;
    const double mean = static_cast<double>(sum / axis.samples.size());
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

void CheckEnoughRows(const std::string& path, const std::vector<AxisSeries>& axes) {
  const size_t rows = axes.empty() ? 0 : axes.front().samples.size();
  if (rows < 2) throw Error(path, 0, "needs at least 2 data rows, found " + std::to_string(rows));
}

// ---- The parallel fast path for large, clean EuRoC files ----------------------------------------

// A read-only memory map of a whole file (empty when mapping fails).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd < 0) return;
    struct stat info;
    if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && info.st_size > 0) {
      void* data =
          ::mmap(nullptr, static_cast<size_t>(info.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (data != MAP_FAILED) {
        data_ = static_cast<const char*>(data);
        size_ = static_cast<size_t>(info.st_size);
        ::madvise(data, size_, MADV_SEQUENTIAL);
      }
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_ != nullptr) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return data_; }
  size_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  size_t size_ = 0;
};

bool IsBlank(char c) { return c == ' ' || c == '\t'; }

// The line [begin, end) without its CR and surrounding blanks; true when it is a data line (not
// blank, not a '#' comment), as TextFileReader::NextLine decides.
bool DataLine(const char** begin, const char** end) {
  while (*begin < *end && IsBlank(**begin)) ++*begin;
  while (*end > *begin && (IsBlank((*end)[-1]) || (*end)[-1] == '\r')) --*end;
  return *begin < *end && **begin != '#';
}

// What one thread found in its share of the file.
struct ChunkScan {
  int64_t rows = 0;
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  bool ok = true;
};

// Parses "t,g,g,g,a,a,a" (blanks allowed around commas). False for anything else, which the
// TextFileReader path then reports.
bool ParseEurocRow(const char* p, const char* end, int64_t* t_ns, double* values) {
  auto result = std::from_chars(p, end, *t_ns);
  if (result.ec != std::errc() || *t_ns > kMaxTimestampNs || *t_ns < -kMaxTimestampNs) return false;
  p = result.ptr;
  for (int a = 0; a < 6; ++a) {
    while (p < end && IsBlank(*p)) ++p;
    if (p == end || *p != ',') return false;
    ++p;
    while (p < end && IsBlank(*p)) ++p;
    const auto parsed = std::from_chars(p, end, values[a]);
    // Non-finite or large readings go to the TextFileReader path, which checks the exact
    // plausibility limit and reports the line.
    if (parsed.ec != std::errc() || !(std::abs(values[a]) <= 1e3)) return false;
    p = parsed.ptr;
  }
  return p == end;
}

// Reads a large EuRoC file on all threads; nullopt when the file is small, cannot be mapped, or
// has anything the simple row grammar above does not cover (then the caller reads it again).
std::optional<StaticRecording> ReadEurocParallel(const std::string& path,
                                                 const StaticReadOptions& options) {
  std::error_code error;
  const auto bytes = std::filesystem::file_size(path, error);
  if (error || static_cast<int64_t>(bytes) < options.parallel_min_bytes) return std::nullopt;
  const MappedFile file(path);
  if (file.data() == nullptr) return std::nullopt;
  const char* const data = file.data();
  const size_t size = file.size();
  const int threads = static_cast<int>(std::clamp(std::thread::hardware_concurrency(), 1u, 16u));
  // Chunk boundaries just after a newline.
  std::vector<size_t> bounds(threads + 1, size);
  bounds[0] = 0;
  for (int i = 1; i < threads; ++i) {
    size_t at = std::max(bounds[i - 1], size / threads * i);
    const void* newline = at < size ? std::memchr(data + at, '\n', size - at) : nullptr;
    bounds[i] = newline == nullptr ? size : static_cast<const char*>(newline) - data + 1;
  }
  auto for_each_line = [&](int chunk, auto&& visit) {
    const char* p = data + bounds[chunk];
    const char* const stop = data + bounds[chunk + 1];
    while (p < stop) {
      const void* newline = std::memchr(p, '\n', stop - p);
      const char* line_end = newline == nullptr ? stop : static_cast<const char*>(newline);
      const char* begin = p;
      const char* end = line_end;
      if (DataLine(&begin, &end) && !visit(begin, end)) return false;
      p = line_end + 1;
    }
    return true;
  };
  auto run = [&](auto&& body) {
    std::vector<std::thread> pool;
    for (int i = 1; i < threads; ++i) pool.emplace_back(body, i);
    body(0);
    for (std::thread& thread : pool) thread.join();
  };
  // Pass 1: data rows per chunk (so that every thread writes straight into the final arrays).
  std::vector<ChunkScan> scans(threads);
  run([&](int chunk) {
    scans[chunk].ok = for_each_line(chunk, [&](const char* begin, const char*) {
      // A first data row that is not a number is a header without '#': leave it to the reader.
      if (chunk == 0 && scans[chunk].rows == 0 && !(*begin >= '0' && *begin <= '9')) return false;
      ++scans[chunk].rows;
      return true;
    });
  });
  std::vector<int64_t> offsets(threads + 1, 0);
  for (int i = 0; i < threads; ++i) {
    if (!scans[i].ok) return std::nullopt;
    offsets[i + 1] = offsets[i] + scans[i].rows;
  }
  const int64_t rows = offsets[threads];
  if (rows < 2) return std::nullopt;
  StaticRecording recording;
  recording.source = path;
  recording.axes = MakeAxes(true, true, 3);
  for (AxisSeries& axis : recording.axes) axis.samples.resize(rows);
  double scales[6];
  for (int a = 0; a < 6; ++a) scales[a] = ScaleOf(recording.axes[a], options);
  // Pass 2: parse.
  run([&](int chunk) {
    ChunkScan& scan = scans[chunk];
    int64_t row = offsets[chunk];
    scan.rows = 0;
    scan.ok = for_each_line(chunk, [&](const char* begin, const char* end) {
      int64_t t_ns = 0;
      double values[6];
      if (!ParseEurocRow(begin, end, &t_ns, values)) return false;
      if (scan.rows > 0) {
        if (t_ns <= scan.last_t_ns) return false;
        scan.largest_step_ns = std::max(scan.largest_step_ns, t_ns - scan.last_t_ns);
      } else {
        scan.first_t_ns = t_ns;
      }
      scan.last_t_ns = t_ns;
      ++scan.rows;
      for (int a = 0; a < 6; ++a) recording.axes[a].samples[row] = scales[a] * values[a];
      ++row;
      return true;
    });
  });
  int64_t first_t_ns = 0;
  int64_t last_t_ns = 0;
  int64_t largest_step_ns = 0;
  bool started = false;
  for (const ChunkScan& scan : scans) {
    if (!scan.ok) return std::nullopt;
    if (scan.rows == 0) continue;
    if (started) {
      if (scan.first_t_ns <= last_t_ns) return std::nullopt;
      largest_step_ns = std::max(largest_step_ns, scan.first_t_ns - last_t_ns);
    } else {
      first_t_ns = scan.first_t_ns;
      started = true;
    }
    largest_step_ns = std::max(largest_step_ns, scan.largest_step_ns);
    last_t_ns = scan.last_t_ns;
  }
  const double mean_period_s = 1e-9 * static_cast<double>(last_t_ns - first_t_ns) / (rows - 1);
  // A gap: the reader names its line.
  if (1e-9 * largest_step_ns > options.max_gap_periods * mean_period_s) return std::nullopt;
  recording.rate_hz = 1.0 / mean_period_s;
  CheckAccelUnits(path, recording.axes, options);
  return recording;
}

}  // namespace

const char* ImuSensorName(ImuSensor sensor) {
  return sensor == ImuSensor::kGyroscope ? "gyroscope" : "accelerometer";
}

std::string AxisSeries::name() const {
  return std::string(sensor == ImuSensor::kGyroscope ? "gyro_" : "accel_") + kAxisLetters[axis];
}

StaticRecording ReadEurocStaticRecording(const std::string& path,
                                         const StaticReadOptions& options) {
  CheckScales(options);
  if (std::optional<StaticRecording> fast = ReadEurocParallel(path, options)) {
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
      if (t_ns <= last_t_ns) {
        reader.Fail(
            "timestamps not increasing: " + std::to_string(t_ns) +
                (t_ns == last_t_ns ? " repeats the previous row"
                                   : " is before the previous row's " + std::to_string(last_t_ns)),
            fields[0]);
      }
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
  return recording;
}

StaticRecording ReadColumnStaticRecording(const std::string& path,
                                          double rate_hz,
                                          std::optional<ImuSensor> sensor,
                                          const StaticReadOptions& options) {
  CheckScales(options);
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw Error("the sample rate of plain columns must be positive and finite, got " +
                std::to_string(rate_hz) + " Hz (--rate)");
  }
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

}  // namespace splinecal
