#include "splinecal/imu/static_recording.h"

namespace splinecal {

const char* ImuSensorName(ImuSensor sensor) {
  return sensor == ImuSensor::kGyroscope ? "gyroscope" : "accelerometer";
}

std::string AxisSeries::name() const {
  static const char* const kAxisLetters[] = {"x", "y", "z"};
  return std::string(sensor == ImuSensor::kGyroscope ? "gyro_" : "accel_") + kAxisLetters[axis];
}

}  // namespace splinecal
