// Flags shared by several subcommands (defined once in src/cli/common_flags.cc; gflags refuses a
// flag defined twice). A command lists the ones it accepts in its Command::flags.
#ifndef SPLINECAL_CLI_COMMON_FLAGS_H_
#define SPLINECAL_CLI_COMMON_FLAGS_H_

#include <gflags/gflags.h>

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/bag_imu.h"

#include "splinecal/estimation/imu_noise_mode.h"
#include "splinecal/io/euroc.h"
#include "splinecal/spline/trajectory_model.h"

DECLARE_string(out);
DECLARE_bool(quiet);
DECLARE_string(imu);
DECLARE_string(imu_yaml);
DECLARE_string(bag);
DECLARE_string(imu_topic);
DECLARE_string(bag_time);
DECLARE_string(imu_noise);
DECLARE_string(poses);
DECLARE_double(gravity);
DECLARE_int32(seed);
DECLARE_int32(threads);
DECLARE_double(knot_spacing);
DECLARE_double(duration);
DECLARE_string(accel_unit);
DECLARE_string(gyro_unit);
DECLARE_string(camchain);
DECLARE_string(target);
DECLARE_string(gyro_bias);
DECLARE_string(accel_bias);
DECLARE_string(imu_intrinsics);
DECLARE_string(observations);
DECLARE_double(huber);
DECLARE_int32(min_corners);
DECLARE_string(trajectory);

namespace splinecal {
namespace cli {

// The flag's value, refused with Error("--name: ...") unless finite and > 0 (or >= 0).
double PositiveFlag(const std::string& name, double value);
double NonNegativeFlag(const std::string& name, double value);
// A time span flag [s] (a duration, a start offset, a knot spacing) in int64 nanoseconds: refused
// unless finite, > 0 (>= 0 with allow_zero) and at most 1e9 s (31 years), which keeps its sum
// with any timestamp (at most 4e18 ns, io/text_file.h) far from int64 overflow.
int64_t SpanFlagNs(const std::string& name, double seconds, bool allow_zero = false);
// --threads, refused unless 1 to 256 (the same range in every command).
int ThreadsFlag();
// --knot-spacing [s], checked as a span (SpanFlagNs). 0 means "chosen from the data": accepted
// where the command can choose (can_choose), else refused with a message that says why.
double KnotSpacingFlag(bool can_choose);
// A required path flag: refused when empty.
const std::string& RequiredFlag(const std::string& name, const std::string& value);

// A comma-separated list flag ("a,b,c"); an empty entry is refused with Error("--name: ...").
// Empty text gives an empty list.
std::vector<std::string> ListFlag(const std::string& name, const std::string& text);

// "x,y,z" -> a finite 3-vector; throws Error("--name: ...") otherwise.
Eigen::Vector3d Vector3Flag(const std::string& name, const std::string& text);

// IMU reading options from --accel-unit (m/s^2 | g) and --gyro-unit (rad/s | deg/s). With
// takes_imu_yaml (the command has --imu-yaml), a YAML file given to --imu is refused with a
// pointer to --imu-yaml (Kalibr calls its noise file `--imu`).
ImuReadOptions ImuReadOptionsFromFlags(bool takes_imu_yaml = false);

// Where a command's IMU samples come from (docs/bags.md, "Commands on a bag"): --imu FILE (EuRoC
// imu0/data.csv) or --bag FILE[,FILE...] --imu-topic T [--bag-time header|receive]. Exactly one:
// both given is refused (naming the alternatives, plus `other_inputs` when the command has more,
// e.g. allan's " or --columns FILE"). The bag's source, nullopt without --bag.
std::optional<BagImuSource> BagImuFlags(const std::string& other_inputs = "");
// --imu's path or the bag's "FILE:TOPIC", for results and messages; throws unless exactly one of
// --imu and --bag is given.
std::string ImuInputName();
// The IMU samples of --imu (ReadEurocImu) or --bag (ReadBagImu: the same checks), with
// ImuReadOptionsFromFlags(takes_imu_yaml). Throws when neither or both are given.
std::vector<ImuSample> ReadImuFlags(bool takes_imu_yaml = false);
// The FlagDocs of that choice (--imu, --bag, --imu-topic, --bag-time), for Command::flags.
std::vector<FlagDoc> ImuInputFlags();
// `flags` followed by `more`.
std::vector<FlagDoc> WithFlags(std::vector<FlagDoc> flags, const std::vector<FlagDoc>& more);

// --imu-noise: estimated, reweighted or given (estimation/imu_noise_mode.h).
ImuNoiseMode ImuNoiseModeFlag();

// --trajectory in fit and calibrate: se3 or split (spline/trajectory_model.h).
TrajectoryModel TrajectoryModelFlag();

// The FlagDoc help of --trajectory in fit and calibrate.
inline constexpr const char* kTrajectoryModelHelp =
    "Trajectory model of the spline: se3 (the coupled SE(3) spline, default) or split "
    "(SO(3) x R^3: positions as an ordinary cubic B-spline, Kalibr's and basalt's)";

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_CLI_COMMON_FLAGS_H_
