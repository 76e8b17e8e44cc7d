#include "splinecal/cli/common_flags.h"

#include <cmath>
#include <cstdlib>
#include <sstream>

#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/bag_imu.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/units.h"

DEFINE_string(out,
              "",
              "Output folder [path], created if missing; results appear whole or not at all");
DEFINE_bool(quiet, false, "Silence progress output on stderr");
DEFINE_string(imu, "", "IMU data, EuRoC imu0/data.csv [path]");
DEFINE_string(bag,
              "",
              "The recording, instead of --imu (and detect's --images): a ROS 1 bag (several: one "
              "split recording), an MCAP file, or a rosbag2 folder, its metadata.yaml or its .db3 "
              "files [paths, comma-separated]");
DEFINE_string(imu_topic, "/imu0", "The IMU's ROS topic (sensor_msgs/Imu) in --bag");
DEFINE_string(bag_time,
              "header",
              "Time of a bag message: header (its header stamp, as Kalibr) or receive (the time "
              "the recorder received it)");
DEFINE_string(imu_yaml, "", "IMU noise, Kalibr imu.yaml [path]");
DEFINE_string(imu_noise,
              "estimated",
              "IMU noise: estimated (random walks re-estimated from the residuals, the white "
              "noise measured and used in the standard deviations), reweighted (the measured "
              "white noise also weights the solve) or given (--imu-yaml trusted as it is)");
DEFINE_string(poses, "", "Pose source, EuRoC ground truth or TUM trajectory [path]");
DEFINE_double(gravity,
              splinecal::kDefaultGravity,
              "Gravity magnitude g [m/s^2]; g_w = (0, 0, -g)");
DEFINE_int32(seed, 1, "Random seed; the same seed gives byte-identical output");
DEFINE_int32(threads, 1, "Worker threads, 1 to 256");
DEFINE_double(knot_spacing,
              0.0,
              "Spline knot spacing dt [s]; 0 chooses it from the data (commands with data)");
DEFINE_double(duration, 0.0, "Duration [s] from the start; 0: until the end of the data");
DEFINE_string(accel_unit, "m/s^2", "Unit of the accelerometer columns: m/s^2 or g");
DEFINE_string(camchain, "", "Kalibr camchain.yaml [path]");
DEFINE_string(target, "", "Calibration target: Kalibr aprilgrid YAML or a points YAML [path]");
DEFINE_string(gyro_bias, "0,0,0", "Gyro bias b_g, x,y,z [rad/s]");
DEFINE_string(accel_bias, "0,0,0", "Accelerometer bias b_a, x,y,z [m/s^2]");
DEFINE_string(imu_intrinsics,
              "",
              "IMU models, Kalibr's imu-*.yaml layout (imu0: model, T_i_b, time_offset, "
              "accelerometers, gyroscopes; imu1: ...) [path]");
DEFINE_string(observations,
              "",
              "Detected points, observations.csv: #t_ns,cam_id,point_id,u,v (frame stamp in the "
              "camera clock [ns], pixel [px]) [path]");
DEFINE_double(huber, 2.0, "Huber threshold of the reprojection residuals [px]; 0 disables it");
DEFINE_int32(min_corners, 8, "Frames with fewer target corners are not used");
DEFINE_string(gyro_unit, "rad/s", "Unit of the gyroscope columns: rad/s or deg/s");
// The one flag whose values differ by command (command.h): simulate's motion, or the trajectory
// model fit and calibrate estimate; each command gives its own help text and default.
DEFINE_string(trajectory,
              "",
              "The trajectory: simulate's motion, or the spline model of fit and calibrate");

namespace splinecal {
namespace cli {

double PositiveFlag(const std::string& name, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    throw Error("--" + name + ": must be a positive number, got " + std::to_string(value));
  }
  return value;
}

double NonNegativeFlag(const std::string& name, double value) {
  if (!std::isfinite(value) || value < 0.0) {
    throw Error("--" + name + ": must be zero or positive, got " + std::to_string(value));
  }
  return value;
}

int64_t SpanFlagNs(const std::string& name, double seconds, bool allow_zero) {
  constexpr double kMaxSpanS = 1e9;
  seconds = allow_zero ? NonNegativeFlag(name, seconds) : PositiveFlag(name, seconds);
  if (seconds > kMaxSpanS) {
    throw Error("--" + name + ": at most 1e9 s, got " + std::to_string(seconds));
  }
  return static_cast<int64_t>(std::llround(seconds * 1e9));
}

int ThreadsFlag() {
  constexpr int kMaxThreads = 256;
  if (FLAGS_threads < 1 || FLAGS_threads > kMaxThreads) {
    throw Error("--threads: expected 1 to 256, got " + std::to_string(FLAGS_threads));
  }
  return FLAGS_threads;
}

double KnotSpacingFlag(bool can_choose) {
  if (FLAGS_knot_spacing == 0.0 && !can_choose) {
    throw Error(
        "--knot-spacing: 0 (chosen from the IMU data) needs IMU data to choose from; give the "
        "spacing in seconds");
  }
  SpanFlagNs("knot-spacing", FLAGS_knot_spacing, /*allow_zero=*/can_choose);
  return FLAGS_knot_spacing;
}

std::vector<std::string> ListFlag(const std::string& name, const std::string& text) {
  std::vector<std::string> items;
  if (text.empty()) return items;
  for (size_t begin = 0;;) {
    const size_t comma = text.find(',', begin);
    items.push_back(text.substr(begin, comma - begin));
    if (items.back().empty()) throw Error("--" + name + ": empty entry in '" + text + "'");
    if (comma == std::string::npos) return items;
    begin = comma + 1;
  }
}

const std::string& RequiredFlag(const std::string& name, const std::string& value) {
  if (value.empty()) throw Error("--" + name + " is required");
  return value;
}

Eigen::Vector3d Vector3Flag(const std::string& name, const std::string& text) {
  Eigen::Vector3d v;
  std::stringstream stream(text);
  std::string item;
  int i = 0;
  while (std::getline(stream, item, ',')) {
    char* end = nullptr;
    const double value = std::strtod(item.c_str(), &end);
    if (i >= 3 || item.empty() || *end != '\0' || !std::isfinite(value)) {
      throw Error("--" + name + ": expected three finite numbers x,y,z, got '" + text + "'");
    }
    v[i++] = value;
  }
  if (i != 3) throw Error("--" + name + ": expected three numbers x,y,z, got '" + text + "'");
  return v;
}

TrajectoryModel TrajectoryModelFlag() {
  TrajectoryModel model = TrajectoryModel::kSE3;
  if (!ParseTrajectoryModel(FLAGS_trajectory, &model)) {
    throw Error("--trajectory: expected se3 or split, got '" + FLAGS_trajectory + "'");
  }
  return model;
}

ImuNoiseMode ImuNoiseModeFlag() {
  ImuNoiseMode mode = ImuNoiseMode::kEstimated;
  if (ValueNamed(kImuNoiseModeNames, FLAGS_imu_noise, &mode)) return mode;
  throw Error("--imu-noise: expected " + JoinNames(kImuNoiseModeNames, ", ") + ", got '" +
              FLAGS_imu_noise + "'");
}

ImuReadOptions ImuReadOptionsFromFlags(bool takes_imu_yaml) {
  ImuReadOptions options = ImuUnitReadOptions(FLAGS_accel_unit, FLAGS_gyro_unit);
  if (takes_imu_yaml) {
    options.yaml_hint =
        "IMU noise densities (Kalibr's imu.yaml) go to --imu-yaml; --imu takes the IMU samples, "
        "EuRoC imu0/data.csv";
  }
  return options;
}

std::optional<BagImuSource> BagImuFlags(const std::string& other_inputs) {
  const std::string alternatives = "--imu FILE or --bag FILE --imu-topic T" + other_inputs;
  if (!FLAGS_imu.empty() && !FLAGS_bag.empty()) {
    throw Error("--imu and --bag both given: the IMU samples come from one of " + alternatives);
  }
  if (FLAGS_bag.empty()) return std::nullopt;
  BagImuSource source;
  source.paths = ListFlag("bag", FLAGS_bag);
  source.topic = RequiredFlag("imu-topic", FLAGS_imu_topic);
  source.time = ParseBagTime(FLAGS_bag_time);
  return source;
}

std::string ImuInputName() {
  const std::optional<BagImuSource> bag = BagImuFlags();
  if (bag.has_value()) return bag->Name();
  if (FLAGS_imu.empty()) {
    throw Error("--imu is required (or --bag FILE --imu-topic T: the IMU from a recording)");
  }
  return FLAGS_imu;
}

std::vector<ImuSample> ReadImuFlags(bool takes_imu_yaml) {
  ImuInputName();  // exactly one of --imu and --bag
  const std::optional<BagImuSource> bag = BagImuFlags();
  if (!bag.has_value()) return ReadEurocImu(FLAGS_imu, ImuReadOptionsFromFlags(takes_imu_yaml));
  return ReadBagImu(*bag, ImuReadOptionsFromFlags(takes_imu_yaml));
}

std::vector<FlagDoc> ImuInputFlags() {
  return {{"imu", "IMU samples, EuRoC imu0/data.csv [path]; or --bag"},
          {"bag", "IMU samples from a recording instead of --imu: a ROS 1 bag (several: one split "
                  "recording), an MCAP file, or a rosbag2 folder, metadata.yaml or .db3 files "
                  "[paths, comma-separated]"},
          {"imu_topic", ""},
          {"bag_time", ""}};
}

std::vector<FlagDoc> WithFlags(std::vector<FlagDoc> flags, const std::vector<FlagDoc>& more) {
  flags.insert(flags.end(), more.begin(), more.end());
  return flags;
}

}  // namespace cli
}  // namespace splinecal
