// The IMU columns' units as the commands name them (--accel-unit m/s^2|g, --gyro-unit
// rad/s|deg/s): the reader's scales (io/euroc.h). The command line and the Python module both
// read the names through ImuUnitReadOptions.
#ifndef SPLINECAL_IO_IMU_UNITS_H_
#define SPLINECAL_IO_IMU_UNITS_H_

#include <string>

#include "splinecal/io/euroc.h"

namespace splinecal {

// The g of "units of g" [m/s^2].
inline constexpr double kStandardGravity = 9.80665;

// Read options with gyro_scale and accel_scale for the units named (accel in g: the units check
// is off, the data is known to be in g). Throws splinecal::Error naming --accel-unit or
// --gyro-unit for another name.
ImuReadOptions ImuUnitReadOptions(const std::string& accel_unit, const std::string& gyro_unit);

}  // namespace splinecal

#endif  // SPLINECAL_IO_IMU_UNITS_H_
