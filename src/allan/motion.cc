#include "splinecal/allan/motion.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <vector>

#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

struct WindowStats {
  std::vector<double> means;
  double white_sigma = 0.0;  // median over windows of std(first differences) / sqrt(2)
};

WindowStats Windows(const std::vector<double>& y, int64_t n) {
  WindowStats stats;
  const int64_t count = static_cast<int64_t>(y.size()) / n;
  stats.means.resize(count);
  std::vector<double> white(count);
  for (int64_t w = 0; w < count; ++w) {
    const double* x = y.data() + w * n;
    // Sums relative to the window's first sample keep the arithmetic well conditioned when a
    // large constant (gravity) rides on small noise.
    double sum = 0.0;
    double diff_sum = 0.0;
    double diff_squares = 0.0;
    for (int64_t i = 0; i < n; ++i) {
      sum += x[i] - x[0];
      if (i > 0) {
        const double d = x[i] - x[i - 1];
        diff_sum += d;
        diff_squares += d * d;
      }
    }
    stats.means[w] = x[0] + sum / n;
    const double k = static_cast<double>(n - 1);
    const double variance = std::max(0.0, (diff_squares - diff_sum * diff_sum / k) / (k - 1.0));
    white[w] = std::sqrt(0.5 * variance);
  }
  std::nth_element(white.begin(), white.begin() + count / 2, white.end());
  stats.white_sigma = white[count / 2];
  return stats;
}

}  // namespace

std::string MotionCheck::Summary(const MotionOptions& options) const {
  if (!checked) return "too short to check for motion (fewer than 3 windows)";
  std::string text = StringPrintf(
      "%s: consecutive %.3g s means differ by up to %.0f times what its white noise explains (at "
      "t = %.1f s; threshold %.0f); %lld of %lld windows beyond, the first at t = %.1f s",
      worst_axis.c_str(),
      options.window_s,
      worst_ratio,
      worst_at_s,
      options.threshold_sigmas,
      static_cast<long long>(moving_windows),
      static_cast<long long>(windows),
      first_moving_at_s);
  if (max_tilt_deg > 0.0) text += StringPrintf("; gravity turns by up to %.2g deg", max_tilt_deg);
  return text;
}

MotionCheck CheckMotion(const StaticRecording& recording, const MotionOptions& options) {
  MotionCheck check;
  if (recording.axes.empty() || !(recording.rate_hz > 0.0)) return check;
  const int64_t n =
      std::max<int64_t>(kMinWindowSamples, std::llround(options.window_s * recording.rate_hz));
  const int64_t samples = static_cast<int64_t>(recording.axes.front().samples.size());
  if (samples / n < 3) return check;
  check.checked = true;
  check.windows = samples / n;
  double window_s = static_cast<double>(n) / recording.rate_hz;
  check.first_moving_at_s = -1.0;
  std::array<const std::vector<double>*, 3> accel_means = {nullptr, nullptr, nullptr};
  std::vector<WindowStats> all(recording.axes.size());
  std::vector<bool> moving(check.windows, false);
  for (size_t a = 0; a < recording.axes.size(); ++a) {
    const AxisSeries& axis = recording.axes[a];
    all[a] = Windows(axis.samples, n);
    const WindowStats& stats = all[a];
    if (axis.sensor == ImuSensor::kAccelerometer) accel_means[axis.axis] = &stats.means;
    const double expected = std::sqrt(2.0 / static_cast<double>(n)) * stats.white_sigma;
    for (int64_t w = 1; w < check.windows; ++w) {
      const double difference = std::abs(stats.means[w] - stats.means[w - 1]);
      // A white level of 0 (a quantised axis that never changes within a window) makes any
      // change infinitely large: compare with the smallest positive level instead.
      const double ratio = difference / std::max(expected, 1e-300);
      if (ratio > check.worst_ratio) {
        check.worst_ratio = ratio;
        check.worst_axis = axis.name();
        check.worst_at_s = static_cast<double>(w) * window_s;
      }
      if (ratio > options.threshold_sigmas) moving[w] = true;
    }
  }
  for (int64_t w = 0; w < check.windows; ++w) {
    if (!moving[w]) continue;
    ++check.moving_windows;
    if (check.first_moving_at_s < 0.0) check.first_moving_at_s = static_cast<double>(w) * window_s;
  }
  check.moving = check.moving_windows > 0;
  if (check.first_moving_at_s < 0.0) check.first_moving_at_s = 0.0;
  if (accel_means[0] && accel_means[1] && accel_means[2]) {
    for (int64_t w = 1; w < check.windows; ++w) {
      double dot = 0.0, a2 = 0.0, b2 = 0.0;
      for (int k = 0; k < 3; ++k) {
        const double a = (*accel_means[k])[w - 1];
        const double b = (*accel_means[k])[w];
        dot += a * b;
        a2 += a * a;
        b2 += b * b;
      }
      if (a2 > 0.0 && b2 > 0.0) {
        const double cosine = std::clamp(dot / std::sqrt(a2 * b2), -1.0, 1.0);
        check.max_tilt_deg = std::max(check.max_tilt_deg, std::acos(cosine) * kRadToDeg);
      }
    }
  }
  return check;
}

}  // namespace splinecal
