// The text files of `splinecal allan --out DIR` (report/allan_report.h): allan.csv, result.yaml,
// imu.yaml.
#include "splinecal/report/allan_report.h"

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include "splinecal/allan/allan.h"
#include "splinecal/allan/detail/sensor_units.h"
#include "splinecal/axis_name.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/report/option_names.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

using internal::SensorUnits;
using internal::UnitsOf;

void WriteEstimate(const std::string& key, const TermEstimate& estimate, YamlWriter* yaml) {
  if (estimate.identified) {
    yaml->Scalar(key, estimate.value);
    Eigen::VectorXd pair(2);
    pair << estimate.value_low, estimate.value_high;
    yaml->Vector(key + "_interval", pair);
    pair << estimate.tau_min_s, estimate.tau_max_s;
    yaml->Vector(key + "_tau_range_s", pair);
    yaml->Scalar(key + "_points", estimate.num_points);
    yaml->Scalar(key + "_measured_slope", estimate.measured_slope);
  } else {
    yaml->Scalar(key, std::string("not identified"));
    yaml->Scalar(key + "_reason", estimate.reason);
  }
  yaml->Scalar(key + "_upper_bound", estimate.upper_bound);
  if (!estimate.model_note.empty()) yaml->Scalar(key + "_model_disagrees", estimate.model_note);
}

void WriteModelEstimate(const std::string& key, const TermEstimate& estimate, YamlWriter* yaml) {
  if (estimate.identified) {
    yaml->Scalar(key, estimate.value);
    Eigen::VectorXd range(2);
    range << estimate.tau_min_s, estimate.tau_max_s;
    yaml->Vector(key + "_tau_range_s", range);
  } else {
    yaml->Scalar(key, std::string("not identified"));
    yaml->Scalar(key + "_reason", estimate.reason);
  }
}

void WriteKalibrKey(const std::string& key, const KalibrKey& value, YamlWriter* yaml) {
  if (!value.present) return;
  yaml->Scalar(key, value.value);
  yaml->Scalar(key + "_is_upper_bound", value.upper_bound);
  yaml->Scalar(key + "_axes", value.upper_bound ? std::string("none identified") : value.axes);
  if (value.unreliable) yaml->Scalar(key + "_unreliable", true);
}

// The comment imu.yaml carries for a key: where its value comes from.
std::string KeyComment(const char* name, const KalibrKey& key, CombineAxes combine) {
  if (!key.present) return "";
  std::string text = std::string("# ") + name + ": ";
  if (key.upper_bound) {
    text +=
        "UPPER BOUND, no axis shows the slope of this term (the largest of the axes' bounds; "
        "see result.yaml for why)";
  } else {
    text += std::string(NameOf(kCombineAxesNames, combine)) + " over the identified " +
            (key.num_axes == 1 ? "axis " : "axes ") + key.axes;
  }
  if (key.unreliable) text += "; UNRELIABLE: the recording moves";
  return text + "\n";
}

// The work budget (allan/work_budget.h): what the deviation evaluated per axis, in passes (N
// terms each), and which averaging times were strided (per averaging time: allan.csv).
void WriteWorkBudget(const AllanResult& result, YamlWriter* yaml) {
  yaml->Scalar("max_passes", result.max_passes);
  if (result.axes.empty()) return;
  const AllanCurve& curve = result.axes.front().curve;
  int64_t overlapping = 0;
  int64_t used = 0;
  int strided = 0;
  Eigen::VectorXd tau_range(2);
  Eigen::VectorXd stride_range(2);
  for (size_t i = 0; i < curve.strides.size(); ++i) {
    overlapping += AllanTermCount(curve.num_samples, curve.cluster_sizes[i], 1);
    used += curve.num_terms[i];
    if (curve.strides[i] == 1) continue;
    const double stride = static_cast<double>(curve.strides[i]);
    if (strided++ == 0) {
      tau_range << curve.tau_s[i], curve.tau_s[i];
      stride_range << stride, stride;
    }
    tau_range[1] = std::max(tau_range[1], curve.tau_s[i]);
    stride_range[0] = std::min(stride_range[0], stride);
    stride_range[1] = std::max(stride_range[1], stride);
  }
  const double n = static_cast<double>(curve.num_samples);
  yaml->Comment("passes of N second differences per axis: all start indices, and those used");
  yaml->Scalar("overlapping_passes", static_cast<double>(overlapping) / n);
  yaml->Scalar("passes_used", static_cast<double>(used) / n);
  yaml->Scalar("strided_averaging_times", strided);
  if (strided > 0) {
    yaml->Comment("every s-th start index (s: stride, per averaging time in allan.csv)");
    yaml->Vector("strided_tau_range_s", tau_range);
    yaml->Vector("stride_range", stride_range);
  }
}

}  // namespace

std::string AllanCsvText(const AllanResult& result) {
  std::string text = "#tau_s";
  for (const AxisAllan& axis : result.axes) text += "," + axis.name;
  for (const AxisAllan& axis : result.axes) text += "," + axis.name + "_low";
  for (const AxisAllan& axis : result.axes) text += "," + axis.name + "_high";
  text += ",stride,terms\n";
  const size_t rows = result.axes.empty() ? 0 : result.axes.front().curve.tau_s.size();
  for (size_t i = 0; i < rows; ++i) {
    text += FormatDouble(result.axes.front().curve.tau_s[i]);
    for (const AxisAllan& axis : result.axes) text += "," + FormatDouble(axis.curve.adev[i]);
    for (const AxisAllan& axis : result.axes) text += "," + FormatDouble(axis.fit.adev_low[i]);
    for (const AxisAllan& axis : result.axes) text += "," + FormatDouble(axis.fit.adev_high[i]);
    const AllanCurve& curve = result.axes.front().curve;
    text +=
        "," + std::to_string(curve.strides[i]) + "," + std::to_string(curve.num_terms[i]) + "\n";
  }
  return text;
}

std::string AllanResultYamlText(const AllanResult& result) {
  YamlWriter yaml;
  yaml.Comment("splinecal allan: IMU noise from the overlapping Allan deviation (docs/allan.md)");
  yaml.Comment("Densities in Kalibr's continuous-time units, not per-sample standard deviations.");
  if (!result.source.empty()) yaml.Scalar("source", result.source);
  yaml.Scalar("update_rate", result.rate_hz);
  yaml.Scalar("num_samples", result.num_samples);
  yaml.Scalar("duration_s", result.num_samples / result.rate_hz);
  yaml.Scalar("start_s", result.start_s);
  yaml.Scalar("end_s", result.end_s);
  yaml.Scalar("taus_per_decade", result.taus_per_decade);
  yaml.Scalar("max_tau_fraction", result.max_tau_fraction);
  WriteWorkBudget(result, &yaml);
  yaml.Scalar("combine", std::string(NameOf(kCombineAxesNames, result.combine)));
  yaml.Scalar("motion_detected", result.motion.moving);
  if (result.motion.moving) {
    yaml.Scalar("motion", result.motion.Summary());
    yaml.Comment("The recording moves: every term below is UNRELIABLE.");
  }
  yaml.Comment("Kalibr keys: the slope-line values of the identified axes combined; an upper");
  yaml.Comment("bound when no axis identified the term ([rad/s/sqrt(Hz)], [rad/s^2/sqrt(Hz)],");
  yaml.Comment("[m/s^2/sqrt(Hz)], [m/s^3/sqrt(Hz)]).");
  WriteKalibrKey("gyroscope_noise_density", result.gyroscope_noise_density, &yaml);
  WriteKalibrKey("gyroscope_random_walk", result.gyroscope_random_walk, &yaml);
  WriteKalibrKey("accelerometer_noise_density", result.accelerometer_noise_density, &yaml);
  WriteKalibrKey("accelerometer_random_walk", result.accelerometer_random_walk, &yaml);
  for (const ImuSensor sensor : {ImuSensor::kGyroscope, ImuSensor::kAccelerometer}) {
    bool any = false;
    for (const AxisAllan& axis : result.axes) any = any || axis.sensor == sensor;
    if (!any) continue;
    const SensorUnits& units = UnitsOf(sensor);
    yaml.BeginMap(ImuSensorName(sensor));
    yaml.BeginMap("units");
    yaml.Scalar("mean", std::string(units.adev));
    for (int j = 0; j < kNumNoiseTerms; ++j) {
      const NoiseTerm term = static_cast<NoiseTerm>(j);
      yaml.Scalar(NoiseTermKey(term), std::string(units.Of(term)));
    }
    yaml.EndMap();
    for (const AxisAllan& axis : result.axes) {
      if (axis.sensor != sensor) continue;
      yaml.BeginMap(AxisName(axis.axis));
      yaml.Scalar("mean", axis.mean);
      if (result.motion.moving) yaml.Scalar("unreliable", std::string("the recording moves"));
      yaml.Scalar("filter_dip_below_tau_s", axis.fit.filter_dip_tau_s);
      yaml.Comment(
          "slope lines through the 90% intervals: Q slope -1, N -1/2 (at tau = 1 s), B 0 "
          "(floor / 0.664), K +1/2 (at tau = 3 s), R +1");
      for (int j = 0; j < kNumNoiseTerms; ++j) {
        const NoiseTerm term = static_cast<NoiseTerm>(j);
        WriteEstimate(NoiseTermKey(term), axis.fit[term], &yaml);
      }
      yaml.Comment("second opinion: weighted least-squares fit of the IEEE Std 952 model");
      yaml.BeginMap("model");
      for (int j = 0; j < kNumNoiseTerms; ++j) {
        WriteModelEstimate(NoiseTermKey(static_cast<NoiseTerm>(j)), axis.fit.model_terms[j], &yaml);
      }
      yaml.Scalar("rms_log_error", axis.fit.model_rms_log_error);
      yaml.EndMap();
      yaml.EndMap();
    }
    yaml.EndMap();
  }
  return yaml.str();
}

std::string AllanImuYamlText(const AllanResult& result) {
  const bool gyro = result.gyroscope_noise_density.present;
  const bool accel = result.accelerometer_noise_density.present;
  std::string text;
  if (gyro && accel) {
    ImuNoise noise;
    noise.gyroscope_noise_density = result.gyroscope_noise_density.value;
    noise.gyroscope_random_walk = result.gyroscope_random_walk.value;
    noise.accelerometer_noise_density = result.accelerometer_noise_density.value;
    noise.accelerometer_random_walk = result.accelerometer_random_walk.value;
    noise.update_rate_hz = result.rate_hz;
    text = ImuYamlText(noise);
  } else {
    const char* prefix = gyro ? "gyroscope" : "accelerometer";
    const SensorUnits& units = UnitsOf(gyro ? ImuSensor::kGyroscope : ImuSensor::kAccelerometer);
    const KalibrKey& density =
        gyro ? result.gyroscope_noise_density : result.accelerometer_noise_density;
    const KalibrKey& walk = gyro ? result.gyroscope_random_walk : result.accelerometer_random_walk;
    text += "# IMU noise in Kalibr's continuous-time densities (written by splinecal)\n";
    text += std::string("# only ") + prefix + " columns were given\n";
    text += std::string(prefix) + "_noise_density: " + FormatDouble(density.value) + "  # [" +
            units.density + "]\n";
    text += std::string(prefix) + "_random_walk: " + FormatDouble(walk.value) + "  # [" +
            units.walk + "]\n";
    text += "update_rate: " + FormatDouble(result.rate_hz) + "  # [Hz]\n";
  }
  const std::pair<const char*, const KalibrKey*> keys[] = {
      {"gyroscope_noise_density", &result.gyroscope_noise_density},
      {"gyroscope_random_walk", &result.gyroscope_random_walk},
      {"accelerometer_noise_density", &result.accelerometer_noise_density},
      {"accelerometer_random_walk", &result.accelerometer_random_walk}};
  for (const auto& [name, key] : keys) text += KeyComment(name, *key, result.combine);
  return text;
}

}  // namespace splinecal
