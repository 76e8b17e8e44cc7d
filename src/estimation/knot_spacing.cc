#include "splinecal/estimation/knot_spacing.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>

#include "splinecal/imu/imu_rate.h"
#include "splinecal/string_printf.h"

namespace splinecal {

namespace {

// Candidates of the automatic knot spacing [s], largest first (docs/fit.md, "Knot spacing").
constexpr double kKnotSpacingCandidates[] = {0.2, 0.1, 0.05, 0.04, 0.025, 0.02, 0.01};
// Share of the gyro signal's variance a knot interval may leave unexplained.
constexpr double kKnotSpacingUnexplainedShare = 0.01;

}  // namespace

double ChooseKnotSpacing(const std::vector<ImuSample>& imu,
                         const ImuNoise& noise,
                         std::string* rule) {
  CHECK_GE(imu.size(), 2u);
  const double rate_hz = ImuRateHz(imu);
  CHECK_GT(rate_hz, 0.0);
  const int n = static_cast<int>(imu.size());
  // Prefix sums of the gyro for O(1) window means.
  std::vector<Eigen::Vector3d> prefix(n + 1, Eigen::Vector3d::Zero());
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) {
    prefix[k + 1] = prefix[k] + imu[k].gyro;
    mean += imu[k].gyro;
  }
  mean /= n;
  double variance = 0.0;
  for (int k = 0; k < n; ++k) variance += (imu[k].gyro - mean).squaredNorm();
  variance /= 3.0 * n;
  const double noise_variance =
      noise.gyroscope_noise_density * noise.gyroscope_noise_density * rate_hz;
  const double signal_variance = std::max(0.0, variance - noise_variance);
  const double allowed = std::max(kKnotSpacingUnexplainedShare * signal_variance, noise_variance);
  const double min_spacing = 2.0 / rate_hz;

  double chosen = 0.0;
  double chosen_unexplained = 0.0;
  double smallest = 0.0;
  double smallest_unexplained = 0.0;
  for (double dt : kKnotSpacingCandidates) {
    if (dt < min_spacing * (1.0 - 1e-9)) continue;
    const int m = std::max(1, static_cast<int>(std::lround(dt * rate_hz)));
    if (m > n) continue;
    const int half = m / 2;
    double sum = 0.0;
    int count = 0;
    for (int k = half; k + (m - 1 - half) < n; ++k) {
      const int first = k - half;
      const Eigen::Vector3d average = (prefix[first + m] - prefix[first]) / m;
      sum += (imu[k].gyro - average).squaredNorm();
      ++count;
    }
    if (count == 0) continue;
    const double residual = sum / (3.0 * count);
    // A sample's white noise contributes sigma^2 (1 - 1/m) to its distance from the mean of a
    // window that contains it.
    const double unexplained = std::max(0.0, residual - noise_variance * (1.0 - 1.0 / m));
    smallest = dt;
    smallest_unexplained = unexplained;
    if (unexplained <= allowed) {
      chosen = dt;
      chosen_unexplained = unexplained;
      break;
    }
  }
  bool fallback = false;
  if (chosen == 0.0) {
    fallback = true;
    chosen = smallest > 0.0 ? smallest : std::max(min_spacing, 0.01);
    chosen_unexplained = smallest_unexplained;
  }
  if (rule != nullptr) {
    std::ostringstream text;
    text << "automatic: " << chosen << " s, ";
    if (fallback) {
      text << "the smallest candidate (no candidate captured the gyro signal to within "
              "max(1% of its variance, the gyro noise variance))";
    } else {
      text << "the largest of 0.2, 0.1, 0.05, 0.04, 0.025, 0.02, 0.01 s (>= 2 IMU periods) whose "
              "one-interval moving average leaves <= max(1% of the gyro signal variance, the gyro "
              "noise variance) unexplained";
    }
    const double share = signal_variance > 0.0 ? chosen_unexplained / signal_variance : 0.0;
    text << " (" << StringPrintf("%.2g", 100.0 * share) << "% of the gyro signal variance left)";
    *rule = text.str();
  }
  return chosen;
}

}  // namespace splinecal
