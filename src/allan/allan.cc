#include "splinecal/allan/allan.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <exception>
#include <mutex>
#include <thread>
#include <utility>

#include "splinecal/error.h"
#include "splinecal/imu/noise.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// The noise fit needs a curve: fewer averaging times than this is refused as too short.
constexpr int kMinAveragingTimes = 3;

struct Units {
  const char* adev;     // deviation and B [rad/s]
  const char* density;  // N
  const char* walk;     // K
  const char* quantization;
  const char* ramp;
  const char* adev_svg;  // the same with typographic symbols, for the plot
  const char* density_svg;
  const char* walk_svg;
};

const Units& UnitsOf(ImuSensor sensor) {
  static const Units kGyro = {"rad/s",
                              "rad/s/sqrt(Hz)",
                              "rad/s^2/sqrt(Hz)",
                              "rad",
                              "rad/s^2",
                              "rad/s",
                              "rad/s/√Hz",
                              "rad/s²/√Hz"};
  static const Units kAccel = {
      "m/s^2", "m/s^2/sqrt(Hz)", "m/s^3/sqrt(Hz)", "m/s", "m/s^3", "m/s²", "m/s²/√Hz", "m/s³/√Hz"};
  return sensor == ImuSensor::kGyroscope ? kGyro : kAccel;
}

const char* const kAxisLetters[] = {"x", "y", "z"};

// Combines one key over the axes of `sensor`.
KalibrKey Combine(const std::vector<AxisAllan>& axes,
                  ImuSensor sensor,
                  bool random_walk,
                  CombineAxes combine) {
  KalibrKey key;
  std::vector<double> identified;
  std::vector<double> bounds;
  for (const AxisAllan& axis : axes) {
    if (axis.sensor != sensor) continue;
    key.present = true;
    const TermEstimate& estimate = random_walk ? axis.fit.random_walk : axis.fit.noise_density;
    if (estimate.identified) identified.push_back(estimate.value);
    bounds.push_back(random_walk ? axis.fit.random_walk_upper_bound
                                 : axis.fit.noise_density_upper_bound);
  }
  if (!key.present) return key;
  const std::vector<double>& values = identified.empty() ? bounds : identified;
  key.upper_bound = identified.empty();
  key.num_axes = static_cast<int>(identified.size());
  if (combine == CombineAxes::kMax) {
    key.value = *std::max_element(values.begin(), values.end());
  } else {
    double sum = 0.0;
    for (const double v : values) sum += v;
    key.value = sum / static_cast<double>(values.size());
  }
  return key;
}

void WriteEstimate(const std::string& key, const TermEstimate& estimate, YamlWriter* yaml) {
  if (estimate.identified) {
    yaml->Scalar(key, estimate.value);
    Eigen::VectorXd range(2);
    range << estimate.tau_min_s, estimate.tau_max_s;
    yaml->Vector(key + "_tau_range_s", range);
    yaml->Scalar(key + "_points", estimate.num_points);
  } else {
    yaml->Scalar(key, std::string("not identifiable"));
    yaml->Scalar(key + "_reason", estimate.reason);
  }
}

void WriteKalibrKey(const std::string& key, const KalibrKey& value, YamlWriter* yaml) {
  if (!value.present) return;
  yaml->Scalar(key, value.value);
  yaml->Scalar(key + "_is_upper_bound", value.upper_bound);
}

}  // namespace

int64_t MinimumSamplesForAveragingTimes(int count, int taus_per_decade, double max_tau_fraction) {
  int64_t low = 1;  // too few
  int64_t high = 2;
  while (static_cast<int>(AllanClusterSizes(high, taus_per_decade, max_tau_fraction).size()) <
         count) {
    low = high;
    high *= 2;
  }
  while (high - low > 1) {
    const int64_t middle = low + (high - low) / 2;
    if (static_cast<int>(AllanClusterSizes(middle, taus_per_decade, max_tau_fraction).size()) >=
        count) {
      high = middle;
    } else {
      low = middle;
    }
  }
  return high;
}

AllanResult ComputeAllan(StaticRecording&& recording, const AllanOptions& options) {
  const std::string& source = recording.source;
  auto fail = [&](const std::string& message) -> Error {
    return source.empty() ? Error(message) : Error(source, 0, message);
  };
  if (recording.axes.empty()) throw fail("no axes to analyse");
  if (!(std::isfinite(recording.rate_hz) && recording.rate_hz > 0.0)) {
    throw fail("sample rate must be positive and finite, got " + std::to_string(recording.rate_hz) +
               " Hz");
  }
  const int64_t n = static_cast<int64_t>(recording.axes.front().samples.size());
  for (const AxisSeries& axis : recording.axes) {
    if (static_cast<int64_t>(axis.samples.size()) != n) {
      throw fail("axes have different lengths (" + std::to_string(n) + " and " +
                 std::to_string(axis.samples.size()) + " samples)");
    }
  }
  std::vector<int64_t> sizes;
  try {
    sizes = AllanClusterSizes(n, options.taus_per_decade, options.max_tau_fraction);
  } catch (const Error& e) {
    throw fail(e.message());
  }
  if (static_cast<int>(sizes.size()) < kMinAveragingTimes) {
    const int64_t needed = MinimumSamplesForAveragingTimes(
        kMinAveragingTimes, options.taus_per_decade, options.max_tau_fraction);
    throw fail(StringPrintf(
        "too few samples for the averaging times: %lld samples (%.4g s at %.6g Hz) give "
        "%d averaging time(s) up to %g of the record; the noise fit needs at least %d, "
        "i.e. at least %lld samples",
        static_cast<long long>(n),
        n / recording.rate_hz,
        recording.rate_hz,
        static_cast<int>(sizes.size()),
        options.max_tau_fraction,
        kMinAveragingTimes,
        static_cast<long long>(needed)));
  }

  AllanResult result;
  result.source = source;
  result.rate_hz = recording.rate_hz;
  result.num_samples = n;
  result.taus_per_decade = options.taus_per_decade;
  result.max_tau_fraction = options.max_tau_fraction;
  result.combine = options.combine;
  const size_t num_axes = recording.axes.size();
  result.axes.resize(num_axes);
  std::vector<std::exception_ptr> errors(num_axes);
  std::atomic<size_t> next{0};
  std::mutex progress_mutex;
  // Axes run in parallel; threads left over (fewer axes than threads) split each axis's passes.
  const int total_threads =
      options.num_threads > 0 ? options.num_threads
                              : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::min<int>(total_threads, static_cast<int>(num_axes));
  const int threads_per_axis = std::max(1, total_threads / threads);
  auto work = [&]() {
    for (size_t a = next++; a < num_axes; a = next++) {
      AxisSeries& series = recording.axes[a];
      AxisAllan& axis = result.axes[a];
      axis.sensor = series.sensor;
      axis.axis = series.axis;
      axis.name = series.name();
      try {
        const IntegratedSignal signal(std::move(series.samples), recording.rate_hz, axis.name);
        axis.mean = signal.mean();
        axis.curve = signal.Deviation(sizes, threads_per_axis);
        axis.fit = FitNoise(axis.curve, options.fit);
      } catch (...) {
        errors[a] = std::current_exception();
        continue;
      }
      if (options.progress) {
        const std::lock_guard<std::mutex> lock(progress_mutex);
        options.progress("allan: " + axis.name + " done (" + std::to_string(sizes.size()) +
                         " averaging times, " + StringPrintf("%.3g", axis.curve.tau_s.front()) +
                         " to " + StringPrintf("%.3g", axis.curve.tau_s.back()) + " s)");
      }
    }
  };
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();
  // The first failing axis in input order, so that the message does not depend on timing.
  for (size_t a = 0; a < num_axes; ++a) {
    if (!errors[a]) continue;
    try {
      std::rethrow_exception(errors[a]);
    } catch (const Error& e) {
      if (source.empty() || !e.path().empty()) throw;
      throw Error(source, 0, e.message());
    }
  }

  result.gyroscope_noise_density =
      Combine(result.axes, ImuSensor::kGyroscope, false, options.combine);
  result.gyroscope_random_walk = Combine(result.axes, ImuSensor::kGyroscope, true, options.combine);
  result.accelerometer_noise_density =
      Combine(result.axes, ImuSensor::kAccelerometer, false, options.combine);
  result.accelerometer_random_walk =
      Combine(result.axes, ImuSensor::kAccelerometer, true, options.combine);
  return result;
}

std::string AllanCsvText(const AllanResult& result) {
  std::string text = "#tau_s";
  for (const AxisAllan& axis : result.axes) text += "," + axis.name;
  for (const AxisAllan& axis : result.axes) text += "," + axis.name + "_err";
  text += "\n";
  const size_t rows = result.axes.empty() ? 0 : result.axes.front().curve.tau_s.size();
  for (size_t i = 0; i < rows; ++i) {
    text += FormatDouble(result.axes.front().curve.tau_s[i]);
    for (const AxisAllan& axis : result.axes) text += "," + FormatDouble(axis.curve.adev[i]);
    for (const AxisAllan& axis : result.axes) text += "," + FormatDouble(axis.curve.adev_error[i]);
    text += "\n";
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
  yaml.Scalar("taus_per_decade", result.taus_per_decade);
  yaml.Scalar("max_tau_fraction", result.max_tau_fraction);
  yaml.Scalar("combine", std::string(result.combine == CombineAxes::kMax ? "max" : "mean"));
  yaml.Comment("Kalibr keys: the slope-line values combined over axes ([rad/s/sqrt(Hz)],");
  yaml.Comment("[rad/s^2/sqrt(Hz)], [m/s^2/sqrt(Hz)], [m/s^3/sqrt(Hz)]).");
  WriteKalibrKey("gyroscope_noise_density", result.gyroscope_noise_density, &yaml);
  WriteKalibrKey("gyroscope_random_walk", result.gyroscope_random_walk, &yaml);
  WriteKalibrKey("accelerometer_noise_density", result.accelerometer_noise_density, &yaml);
  WriteKalibrKey("accelerometer_random_walk", result.accelerometer_random_walk, &yaml);
  for (const ImuSensor sensor : {ImuSensor::kGyroscope, ImuSensor::kAccelerometer}) {
    bool any = false;
    for (const AxisAllan& axis : result.axes) any = any || axis.sensor == sensor;
    if (!any) continue;
    const Units& units = UnitsOf(sensor);
    yaml.BeginMap(ImuSensorName(sensor));
    yaml.BeginMap("units");
    yaml.Scalar("mean", std::string(units.adev));
    yaml.Scalar("quantization", std::string(units.quantization));
    yaml.Scalar("noise_density", std::string(units.density));
    yaml.Scalar("bias_instability", std::string(units.adev));
    yaml.Scalar("random_walk", std::string(units.walk));
    yaml.Scalar("rate_ramp", std::string(units.ramp));
    yaml.EndMap();
    for (const AxisAllan& axis : result.axes) {
      if (axis.sensor != sensor) continue;
      yaml.BeginMap(kAxisLetters[axis.axis]);
      yaml.Scalar("mean", axis.mean);
      yaml.Comment("slope lines: N at tau = 1 s, K at tau = 3 s, B = floor / 0.664");
      WriteEstimate("noise_density", axis.fit.noise_density, &yaml);
      yaml.Scalar("noise_density_upper_bound", axis.fit.noise_density_upper_bound);
      WriteEstimate("random_walk", axis.fit.random_walk, &yaml);
      yaml.Scalar("random_walk_upper_bound", axis.fit.random_walk_upper_bound);
      WriteEstimate("bias_instability", axis.fit.bias_instability, &yaml);
      yaml.Comment("weighted least-squares fit of the IEEE Std 952 model");
      yaml.BeginMap("model");
      for (int j = 0; j < kNumNoiseTerms; ++j) {
        WriteEstimate(NoiseTermKey(static_cast<NoiseTerm>(j)), axis.fit.model_terms[j], &yaml);
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
    const Units& units = UnitsOf(gyro ? ImuSensor::kGyroscope : ImuSensor::kAccelerometer);
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
  for (const auto& [name, key] : keys) {
    if (key->present && key->upper_bound) {
      text += std::string("# ") + name +
              " is an upper bound: no axis shows the slope of that term (record longer); "
              "see result.yaml\n";
    }
  }
  return text;
}

std::string AllanSvgText(const AllanResult& result) {
  plot::Figure figure;
  figure.title = StringPrintf("Allan deviation: %lld samples, %.6g s at %.6g Hz",
                              static_cast<long long>(result.num_samples),
                              result.num_samples / result.rate_hz,
                              result.rate_hz);
  int gyro_axes = 0;
  int accel_axes = 0;
  for (const AxisAllan& axis : result.axes) {
    (axis.sensor == ImuSensor::kGyroscope ? gyro_axes : accel_axes) += 1;
  }
  figure.columns = std::max(1, std::max(gyro_axes, accel_axes));
  for (const AxisAllan& axis : result.axes) {
    const Units& units = UnitsOf(axis.sensor);
    const AllanCurve& curve = axis.curve;
    plot::Panel& panel = figure.panels.emplace_back();
    panel.title =
        std::string(axis.sensor == ImuSensor::kGyroscope ? "gyroscope " : "accelerometer ") +
        kAxisLetters[axis.axis];
    panel.x = {"averaging time τ [s]", plot::Scale::kLog};
    panel.y = {std::string("Allan deviation [") + units.adev_svg + "]", plot::Scale::kLog};
    panel.legend = plot::LegendPosition::kBottomLeft;

    plot::Series& measured = panel.series.emplace_back();
    measured.label = "measured, 1σ error bars";
    measured.color = "#1f77b4";
    measured.marker = plot::Marker::kCircle;
    measured.marker_size = 2.0;
    measured.line_width = 1.0;
    measured.x = curve.tau_s;
    measured.y = curve.adev;
    for (size_t i = 0; i < curve.adev.size(); ++i) {
      measured.y_low.push_back(curve.adev[i] - curve.adev_error[i]);
      measured.y_high.push_back(curve.adev[i] + curve.adev_error[i]);
    }

    // The y range: the measured points in the upper part of the panel, room below them for the
    // legend (kLegendRoom of the height); the fitted lines are clipped to it.
    constexpr double kLegendRoom = 0.4;
    double data_lo = curve.adev.front();
    double data_hi = curve.adev.front();
    for (size_t i = 0; i < curve.adev.size(); ++i) {
      if (curve.adev[i] <= 0.0) continue;
      const double low = measured.y_low[i] > 0.0 ? measured.y_low[i] : curve.adev[i];
      data_lo = data_lo > 0.0 ? std::min(data_lo, low) : low;
      data_hi = std::max(data_hi, measured.y_high[i]);
    }
    if (data_lo > 0.0 && data_hi > data_lo) {
      const double span = std::log10(data_hi / data_lo);
      plot::AutoRange(data_lo / std::pow(10.0, span * kLegendRoom / (1.0 - kLegendRoom)),
                      data_hi,
                      plot::Scale::kLog,
                      &panel.y.min,
                      &panel.y.max);
    }

    const double tau_lo = curve.tau_s.front();
    const double tau_hi = curve.tau_s.back();
    plot::Series& model = panel.series.emplace_back();
    model.label = "IEEE 952 model fit";
    model.color = "#7f7f7f";
    model.line_width = 1.0;
    for (size_t i = 0; i < curve.tau_s.size(); ++i) {
      model.x.push_back(curve.tau_s[i]);
      model.y.push_back(std::sqrt(axis.fit.model.AllanVariance(curve.tau_s[i])));
    }
    std::vector<double> read_x;
    std::vector<double> read_y;
    if (axis.fit.noise_density.identified) {
      const double n = axis.fit.noise_density.value;
      plot::Series& line = panel.series.emplace_back();
      line.label =
          "N = " + StringPrintf("%.3g", n) + " " + units.density_svg + " (slope -1/2, τ = 1 s)";
      line.color = "#d62728";
      line.dashed = true;
      line.x = {tau_lo, tau_hi};
      line.y = {n / std::sqrt(tau_lo), n / std::sqrt(tau_hi)};
      read_x.push_back(1.0);
      read_y.push_back(n);
    }
    if (axis.fit.random_walk.identified) {
      const double k = axis.fit.random_walk.value;
      plot::Series& line = panel.series.emplace_back();
      line.label =
          "K = " + StringPrintf("%.3g", k) + " " + units.walk_svg + " (slope +1/2, τ = 3 s)";
      line.color = "#2ca02c";
      line.dashed = true;
      line.x = {tau_lo, tau_hi};
      line.y = {k * std::sqrt(tau_lo / 3.0), k * std::sqrt(tau_hi / 3.0)};
      read_x.push_back(3.0);
      read_y.push_back(k);
    }
    if (axis.fit.bias_instability.identified) {
      const double b = axis.fit.bias_instability.value;
      plot::Series& line = panel.series.emplace_back();
      line.label = "B = " + StringPrintf("%.3g", b) + " " + units.adev_svg + " (floor / 0.664)";
      line.color = "#ff7f0e";
      line.dashed = true;
      line.x = {tau_lo, tau_hi};
      line.y = {kBiasInstabilityFloor * b, kBiasInstabilityFloor * b};
    }
    if (!read_x.empty()) {
      plot::Series& points = panel.series.emplace_back();
      points.label = "read-off points (τ = 1 s, 3 s)";
      points.color = "#000000";
      points.line = false;
      points.marker = plot::Marker::kSquare;
      points.marker_size = 3.0;
      points.x = read_x;
      points.y = read_y;
    }
  }
  return plot::RenderSvg(figure);
}

}  // namespace splinecal
