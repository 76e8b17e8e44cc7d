// A static IMU recording as `splinecal allan` analyses it: one series per axis at a uniform rate.
// The files are read by io/static_recording.h.
#ifndef SPLINECAL_IMU_STATIC_RECORDING_H_
#define SPLINECAL_IMU_STATIC_RECORDING_H_

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

}  // namespace splinecal

#endif  // SPLINECAL_IMU_STATIC_RECORDING_H_
