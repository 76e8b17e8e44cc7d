// Flags shared by several subcommands (defined once in src/cli/common_flags.cc; gflags refuses a
// flag defined twice). A command lists the ones it accepts in its Command::flags.
#ifndef SPLINECAL_CLI_COMMON_FLAGS_H_
#define SPLINECAL_CLI_COMMON_FLAGS_H_

#include <string>

#include <Eigen/Core>
#include <gflags/gflags.h>

#include "splinecal/io/euroc.h"

DECLARE_string(out);
DECLARE_bool(quiet);
DECLARE_string(imu);
DECLARE_string(imu_yaml);
DECLARE_string(poses);
DECLARE_double(gravity);
DECLARE_int32(seed);
DECLARE_int32(threads);
DECLARE_double(knot_spacing);
DECLARE_string(accel_unit);
DECLARE_string(gyro_unit);
DECLARE_string(camchain);
DECLARE_string(target);
DECLARE_string(gyro_bias);
DECLARE_string(accel_bias);

namespace splinecal {
namespace cli {

// The flag's value, refused with Error("--name: ...") unless finite and > 0 (or >= 0).
double PositiveFlag(const std::string& name, double value);
double NonNegativeFlag(const std::string& name, double value);
// A required path flag: refused when empty.
const std::string& RequiredFlag(const std::string& name, const std::string& value);

// "x,y,z" -> a finite 3-vector; throws Error("--name: ...") otherwise.
Eigen::Vector3d Vector3Flag(const std::string& name, const std::string& text);

// IMU reading options from --accel-unit (m/s^2 | g) and --gyro-unit (rad/s | deg/s).
ImuReadOptions ImuReadOptionsFromFlags();

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_CLI_COMMON_FLAGS_H_
