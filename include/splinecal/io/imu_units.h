// The IMU columns' units as the commands name them (--accel-unit m/s^2|g, --gyro-unit
// rad/s|deg/s): the reader's scales (io/euroc.h), and the check that an accelerometer is not in
// g. The command line and the Python module both read the names through ImuUnitReadOptions.
#ifndef SPLINECAL_IO_IMU_UNITS_H_
#define SPLINECAL_IO_IMU_UNITS_H_

#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/euroc.h"

namespace splinecal {

// The g of "units of g" [m/s^2].
inline constexpr double kStandardGravity = 9.80665;

// Read options with gyro_scale and accel_scale for the units named (accel in g: the units check
// is off, the data is known to be in g). Throws splinecal::Error naming --accel-unit or
// --gyro-unit for another name.
ImuReadOptions ImuUnitReadOptions(const std::string& accel_unit, const std::string& gyro_unit);

// ReadEurocImu's units check (io/euroc.cc), for samples from elsewhere (the Python module's
// arrays): throws splinecal::Error naming `source` when the median accelerometer magnitude is
// near 1 (units of g, not m/s^2).
void CheckAccelNotInG(const std::vector<ImuSample>& samples, const std::string& source);

}  // namespace splinecal

#endif  // SPLINECAL_IO_IMU_UNITS_H_
