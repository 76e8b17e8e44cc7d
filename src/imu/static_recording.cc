#include "splinecal/imu/static_recording.h"

#include <string>

#include "splinecal/axis_name.h"

namespace splinecal {

const char* ImuSensorName(ImuSensor sensor) {
  return sensor == ImuSensor::kGyroscope ? "gyroscope" : "accelerometer";
}

std::string AxisSeries::name() const {
  return std::string(sensor == ImuSensor::kGyroscope ? "gyro_" : "accel_") + AxisName(axis);
}

}  // namespace splinecal
