#include "splinecal/io/imu_units.h"

#include "splinecal/error.h"
#include "splinecal/units.h"

namespace splinecal {

ImuReadOptions ImuUnitReadOptions(const std::string& accel_unit, const std::string& gyro_unit) {
  ImuReadOptions options;
  if (accel_unit == "g") {
    options.accel_scale = kStandardGravity;
    options.check_accel_units = false;
  } else if (accel_unit != "m/s^2") {
    throw Error("--accel-unit: expected m/s^2 or g, got '" + accel_unit + "'");
  }
  if (gyro_unit == "deg/s") {
    options.gyro_scale = kDegToRad;
  } else if (gyro_unit != "rad/s") {
    throw Error("--gyro-unit: expected rad/s or deg/s, got '" + gyro_unit + "'");
  }
  return options;
}

}  // namespace splinecal
