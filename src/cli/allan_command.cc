// `splinecal allan`: IMU noise identification from a static recording (allan/allan.h,
// docs/allan.md). Reads EuRoC imu0/data.csv (--imu) or plain columns (--columns, --rate), writes
// allan.csv, imu.yaml, result.yaml and allan.svg to --out.
#include <gflags/gflags.h>

#include <cmath>
#include <cstdio>
#include <optional>
#include <string>

#include "splinecal/allan/allan.h"
#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/static_recording.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/report/option_names.h"
#include "splinecal/string_printf.h"

DEFINE_int32(taus_per_decade, 10, "Averaging times per decade (before de-duplication)");
DEFINE_int32(max_passes,
             splinecal::kDefaultAllanMaxPasses,
             "Work budget: at most P * N second differences per axis (P passes over the N "
             "samples). Averaging times that fit use every start index (the fully overlapping "
             "estimator); beyond the budget the short ones use every s-th (their EDF and "
             "intervals say so). 0: no budget, always fully overlapping");
DEFINE_double(max_tau_fraction,
              0.1,
              "Longest averaging time as a fraction of the record length, in (0, 0.5]");
DEFINE_string(columns,
              "",
              "Plain text columns without timestamps, whitespace or comma separated: 6 columns "
              "(gyro xyz [rad/s], accel xyz [m/s^2]) or 1 to 3 columns of one sensor (--sensor) "
              "[path]; needs --rate");
DEFINE_double(rate, 0.0, "Sample rate of --columns [Hz]");
DEFINE_string(sensor, "", "Sensor of 1 to 3 --columns: gyro or accel");
DEFINE_double(gyro_scale,
              1.0,
              "Multiplies gyro readings into rad/s (pi/180 = 0.017453292519943295 for deg/s)");
DEFINE_double(accel_scale, 1.0, "Multiplies accel readings into m/s^2 (9.80665 for g)");
DEFINE_string(combine, "mean", "How Kalibr keys combine the identified x, y, z axes: mean or max");
DECLARE_double(start);  // shared with integrate: seconds after the first sample
DEFINE_double(end,
              0.0,
              "End of the stretch to analyse, seconds from the first sample; 0: the end [s]");
DEFINE_bool(allow_motion,
            false,
            "Analyse a recording that moves instead of refusing it; every term is then marked "
            "unreliable");

namespace splinecal {
namespace cli {
namespace {

std::string Summary(const char* name, const KalibrKey& key, const char* unit) {
  if (!key.present) return "";
  std::string note = key.upper_bound ? " (UPPER BOUND: no axis identified it, see result.yaml)"
                                     : " (axes " + key.axes + ")";
  if (key.unreliable) note += " UNRELIABLE: the recording moves";
  return StringPrintf("allan: %-28s %.6g %s%s\n", name, key.value, unit, note.c_str());
}

// What allan reads and checks before computing anything (Command::read_inputs).
struct AllanInputs {
  AllanOptions options;
  StaticRecording recording;
};

AllanInputs ReadAllanInputs() {
  RequiredFlag("out", FLAGS_out);
  const std::optional<BagImuSource> bag = BagImuFlags(" or --columns FILE --rate HZ");
  if (int{!FLAGS_imu.empty()} + int{bag.has_value()} + int{!FLAGS_columns.empty()} != 1) {
    throw Error(
        "give the static recording as --imu FILE (EuRoC imu0/data.csv), as --bag FILE "
        "--imu-topic T, or as --columns FILE --rate HZ: exactly one");
  }
  AllanInputs in;
  AllanOptions& options = in.options;
  options.taus_per_decade = FLAGS_taus_per_decade;
  options.max_tau_fraction = FLAGS_max_tau_fraction;
  if (FLAGS_max_passes < 0) {
    throw Error(
        StringPrintf("--max-passes: expected 0 (no budget) or a positive number of passes, "
                     "got %d",
                     FLAGS_max_passes));
  }
  options.max_passes = FLAGS_max_passes;
  if (!ValueNamed(kCombineAxesNames, FLAGS_combine, &options.combine)) {
    throw Error("--combine: expected " + JoinNames(kCombineAxesNames, " or ") + ", got '" +
                FLAGS_combine + "'");
  }
  options.progress = [](const std::string& line) { Progress(line); };
  options.start_s = FLAGS_start;
  if (FLAGS_end != 0.0) options.end_s = FLAGS_end;
  if (!(options.start_s >= 0.0) || !(options.end_s > options.start_s)) {
    throw Error(StringPrintf(
        "--start %g, --end %g: expected 0 <= start < end (seconds)", FLAGS_start, FLAGS_end));
  }
  options.motion_policy =
      FLAGS_allow_motion ? MotionPolicy::kMarkUnreliable : MotionPolicy::kRefuse;
  // Check the averaging-time flags before reading a large file.
  AllanClusterSizes(1, options.taus_per_decade, options.max_tau_fraction);

  // Units: --gyro-unit / --accel-unit (shared with the other commands) times --gyro-scale /
  // --accel-scale.
  const ImuReadOptions units = ImuReadOptionsFromFlags();
  StaticReadOptions read;
  read.gyro_scale = units.gyro_scale * PositiveFlag("gyro-scale", FLAGS_gyro_scale);
  read.accel_scale = units.accel_scale * PositiveFlag("accel-scale", FLAGS_accel_scale);
  read.check_accel_units = units.check_accel_units;

  StaticRecording& recording = in.recording;
  if (FLAGS_columns.empty() && (FLAGS_rate != 0.0 || !FLAGS_sensor.empty())) {
    throw Error("--rate and --sensor are for --columns; EuRoC files and bags carry timestamps");
  }
  if (bag.has_value()) {
    Progress("allan: reading " + bag->Name());
    recording = ReadBagStaticRecording(*bag, read);
  } else if (!FLAGS_imu.empty()) {
    Progress("allan: reading " + FLAGS_imu);
    recording = ReadEurocStaticRecording(FLAGS_imu, read);
  } else {
    const double rate_hz = PositiveFlag("rate", FLAGS_rate);
    std::optional<ImuSensor> sensor;
    if (FLAGS_sensor == "gyro") {
      sensor = ImuSensor::kGyroscope;
    } else if (FLAGS_sensor == "accel") {
      sensor = ImuSensor::kAccelerometer;
    } else if (!FLAGS_sensor.empty()) {
      throw Error("--sensor: expected gyro or accel, got '" + FLAGS_sensor + "'");
    }
    Progress("allan: reading " + FLAGS_columns);
    recording = ReadColumnStaticRecording(FLAGS_columns, rate_hz, sensor, read);
  }
  return in;
}

int RunAllan() {
  AllanInputs in = ReadAllanInputs();
  StaticRecording& recording = in.recording;
  OutputDir output(FLAGS_out);
  Progress(StringPrintf("allan: %zu axes, %zu samples at %.6g Hz (%.6g s)",
                        recording.axes.size(),
                        recording.axes.front().samples.size(),
                        recording.rate_hz,
                        recording.axes.front().samples.size() / recording.rate_hz));

  const AllanResult result = ComputeAllan(std::move(recording), in.options);
  output.WriteFiles(AllanOutputFiles(result));
  output.Commit();

  const std::string summary =
      Summary("gyroscope_noise_density", result.gyroscope_noise_density, "rad/s/sqrt(Hz)") +
      Summary("gyroscope_random_walk", result.gyroscope_random_walk, "rad/s^2/sqrt(Hz)") +
      Summary("accelerometer_noise_density", result.accelerometer_noise_density, "m/s^2/sqrt(Hz)") +
      Summary("accelerometer_random_walk", result.accelerometer_random_walk, "m/s^3/sqrt(Hz)");
  if (!Quiet()) std::fputs(summary.c_str(), stderr);
  return 0;
}

}  // namespace

Command AllanCommand() {
  Command command;
  command.name = "allan";
  command.summary =
      "IMU noise densities from a static recording (Allan deviation, Kalibr imu.yaml)";
  command.usage =
      "splinecal allan (--imu imu0/data.csv\n"
      "    | --bag FILE [--imu-topic T] [--bag-time header|receive]\n"
      "    | --columns FILE --rate HZ [--sensor gyro|accel])\n"
      "    [--taus-per-decade N] [--max-tau-fraction F] [--max-passes P] [--combine mean|max]\n"
      "    [--gyro-scale S] [--accel-scale S] [--gyro-unit rad/s|deg/s] [--accel-unit m/s^2|g]\n"
      "    [--start S] [--end S] [--allow-motion] --out DIR";
  command.description =
      "Computes the overlapping Allan deviation of every axis at log-spaced averaging times and "
      "decides each noise term from the measured curve: a term (quantization -1, white noise N "
      "-1/2, bias instability B 0, random walk K +1/2, rate ramp +1) is identified only where "
      "the deviation's 90% confidence intervals (equivalent degrees of freedom of the "
      "overlapping estimator) follow its slope over a stated range and rule out the neighbouring "
      "slopes; otherwise it is reported as an upper bound with the reason. The IEEE Std 952 "
      "model fit is a second opinion. A recording that moves is refused (--allow-motion: marked "
      "unreliable); --start/--end cut a static stretch out of a longer log. Beyond a work budget "
      "(--max-passes) the short averaging times use every s-th start index, with intervals from "
      "their own degrees of freedom, so that the time hardly grows with --taus-per-decade. "
      "Writes allan.csv (tau_s, deviation and interval per axis, the stride and number of terms "
      "of each averaging time), imu.yaml (Kalibr densities, not per-sample standard "
      "deviations), result.yaml (every term per axis) and "
      "allan.svg (log-log plot). The recording must be static: the IMU at rest for its whole "
      "length (hours for the random walk). See docs/allan.md.";
  command.flags = {{"imu",
                    "Static recording, EuRoC imu0/data.csv; the rate comes from the "
                    "timestamps [path]"},
                   {"bag",
                    "Static recording in a bag (its --imu-topic, sensor_msgs/Imu): a ROS 1 bag "
                    "(several: one split recording), an MCAP file, or a rosbag2 folder, "
                    "metadata.yaml or .db3 files; the rate comes from the stamps [paths]"},
                   {"imu_topic", ""},
                   {"bag_time", ""},
                   {"columns", ""},
                   {"rate", ""},
                   {"sensor", ""},
                   {"out", ""},
                   {"taus_per_decade", ""},
                   {"max_tau_fraction", ""},
                   {"max_passes", ""},
                   {"combine", ""},
                   {"start",
                    "Start of the stretch to analyse, seconds after the first sample (sample "
                    "index / rate) [s]"},
                   {"end", ""},
                   {"allow_motion", ""},
                   {"gyro_scale", ""},
                   {"accel_scale", ""},
                   {"gyro_unit", ""},
                   {"accel_unit", ""},
                   {"quiet", ""}};
  command.run = &RunAllan;
  command.read_inputs = [] { ReadAllanInputs(); };
  return command;
}

}  // namespace cli
}  // namespace splinecal
