// A static IMU recording as `splinecal allan` reads it: one series per axis at a uniform rate.
//
// Inputs (docs/allan.md):
//   - EuRoC imu0/data.csv (t_ns, gyro xyz [rad/s], accel xyz [m/s^2]); the rate comes from the
//     timestamps: (rows - 1) / (t_last - t_first).
//   - Plain text columns without timestamps, whitespace or comma separated, at a given rate:
//     6 columns are gyro xyz then accel xyz; 1 to 3 columns are the x (y, z) axes of one sensor.
// Both read through the io layer's TextFileReader (blank lines, '#' comments, CRLF, a header row
// without '#'); memory is 8 bytes per sample and axis: 10^8 rows of six axes need 4.8 GB. Large
// EuRoC files take a parallel fast path first (StaticReadOptions::parallel_min_bytes). Readings are
// multiplied by gyro_scale / accel_scale (deg/s -> rad/s: pi / 180; g -> m/s^2: 9.80665).
#ifndef SPLINECAL_ALLAN_STATIC_RECORDING_H_
#define SPLINECAL_ALLAN_STATIC_RECORDING_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace splinecal {

enum class ImuSensor { kGyroscope, kAccelerometer };

// "gyroscope" / "accelerometer" (Kalibr's key prefixes).
const char* ImuSensorName(ImuSensor sensor);

struct AxisSeries {
  ImuSensor sensor = ImuSensor::kGyroscope;
  int axis = 0;                 // 0, 1, 2 for x, y, z
  std::vector<double> samples;  // [rad/s] or [m/s^2]

  // "gyro_x" ... "accel_z": the column names of allan.csv.
  std::string name() const;
};

struct StaticRecording {
  double rate_hz = 0.0;
  std::vector<AxisSeries> axes;  // gyro axes first, then accel axes
  std::string source;            // the file read ("" for data built in memory)
};

struct StaticReadOptions {
  double gyro_scale = 1.0;
  double accel_scale = 1.0;
  // Refuse an accelerometer whose mean reading has a magnitude near 1 (data in g, not m/s^2)
  // unless accel_scale was set.
  bool check_accel_units = true;
  // Refuse a gap between EuRoC timestamps longer than this many mean sample periods: the Allan
  // variance assumes uniform sampling.
  double max_gap_periods = 10.0;
  // EuRoC files at least this large are parsed by all hardware threads at once (the file is
  // mapped and split at line ends); a file the fast path finds anything unusual in (a header row
  // without '#', a bad value, a gap...) is read again by the one-thread TextFileReader path, which
  // reports the error with its line. Both paths give the same numbers, bit for bit.
  int64_t parallel_min_bytes = int64_t{32} << 20;
};

// Throws splinecal::Error with path:line[:column] for: a missing file, a wrong column count, a
// value that is not a finite number, timestamps not strictly increasing, a gap, fewer than 2
// samples, an accelerometer in g.
StaticRecording ReadEurocStaticRecording(const std::string& path,
                                         const StaticReadOptions& options = {});

// `sensor` names the sensor of 1 to 3 columns (required then); 6 columns are gyro xyz then
// accel xyz and take none. rate_hz must be positive and finite. Throws as above, and for 4, 5 or
// more than 6 columns, or for a missing or superfluous sensor.
StaticRecording ReadColumnStaticRecording(const std::string& path,
                                          double rate_hz,
                                          std::optional<ImuSensor> sensor,
                                          const StaticReadOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_STATIC_RECORDING_H_
