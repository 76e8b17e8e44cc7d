// The readers of `splinecal allan`'s static IMU recordings (imu/static_recording.h holds the
// data they fill; docs/allan.md describes the inputs):
//   - EuRoC imu0/data.csv (t_ns, gyro xyz [rad/s], accel xyz [m/s^2]); the rate comes from the
//     timestamps: (rows - 1) / (t_last - t_first).
//   - Plain text columns without timestamps, whitespace or comma separated, at a given rate:
//     6 columns are gyro xyz then accel xyz; 1 to 3 columns are the x (y, z) axes of one sensor.
// Both read through TextFileReader (io/text_file.h: blank lines, '#' comments, CRLF, a header row
// without '#') with the input layer's number parsing and plausibility limits. Memory is 8 bytes
// per sample and axis: 10^8 rows of six axes need 4.8 GB. Large EuRoC files are parsed by all
// threads at once first (io/parallel_euroc_imu.h). Readings are multiplied by gyro_scale /
// accel_scale (deg/s -> rad/s: pi / 180; g -> m/s^2: 9.80665).
#ifndef SPLINECAL_IO_STATIC_RECORDING_H_
#define SPLINECAL_IO_STATIC_RECORDING_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/imu/static_recording.h"
#include "splinecal/io/bag_imu.h"
#include "splinecal/io/euroc.h"

namespace splinecal {

// The EuRoC IMU reader's options (io/euroc.h), read the way a static recording needs: the units
// check looks at the mean accelerometer reading (a static IMU reads gravity) and is skipped when
// accel_scale was set; a gap is measured in mean sample periods (the Allan variance assumes
// uniform sampling).
struct StaticReadOptions : ImuReadOptions {
  // EuRoC files at least this large are parsed by all hardware threads at once; a file that path
  // finds anything unusual in (a header row without '#', a bad value, a gap...) is read again by
  // the one-thread TextFileReader path, which reports the error with its line. Both paths give
  // the same numbers, bit for bit.
  int64_t parallel_min_bytes = int64_t{32} << 20;
};

// Throws splinecal::Error with path:line[:column] for: a missing file, a wrong column count, a
// value that is not a finite number or beyond the plausibility limits, timestamps not strictly
// increasing, a gap, fewer than 2 samples, an accelerometer in g.
StaticRecording ReadEurocStaticRecording(const std::string& path,
                                         const StaticReadOptions& options = {});

// The same from a bag's sensor_msgs/Imu topic (io/bag_imu.h), streamed into the axes: the same
// checks, a gap named with the message after it (its index and time) instead of a line.
StaticRecording ReadBagStaticRecording(const BagImuSource& source,
                                       const StaticReadOptions& options = {});

// `sensor` names the sensor of 1 to 3 columns (required then); 6 columns are gyro xyz then
// accel xyz and take none. rate_hz must be positive and finite. Throws as above, and for 4, 5 or
// more than 6 columns, or for a missing or superfluous sensor.
StaticRecording ReadColumnStaticRecording(const std::string& path,
                                          double rate_hz,
                                          std::optional<ImuSensor> sensor,
                                          const StaticReadOptions& options = {});

// Plain columns already in memory (the Python module's arrays), checked as
// ReadColumnStaticRecording checks a file's: columns[c][i] is sample i of column c, 6 columns
// (gyro xyz, accel xyz, no sensor) or 1 to 3 of `sensor`; every reading scaled, finite and within
// the input layer's plausibility limits; rate_hz positive and finite; at least 2 samples; an
// accelerometer in g refused. `source` names the data in errors and in the result.
StaticRecording StaticRecordingFromColumns(const std::vector<std::vector<double>>& columns,
                                           double rate_hz,
                                           std::optional<ImuSensor> sensor,
                                           const std::string& source,
                                           const StaticReadOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_IO_STATIC_RECORDING_H_
