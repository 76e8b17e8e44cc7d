#include "splinecal/sim/noise_generator.h"

#include <cmath>
#include <string>

#include "splinecal/error.h"
#include "splinecal/units.h"

namespace splinecal {
namespace internal {

namespace {

// The right edge of the base strip for 256 strips [Marsaglia00, section 4]: the r for which the
// recursion below closes at the top, f(x[255]) + v / x[255] = f(0) = 1. With this r the closing
// error is below 1e-12 (checked in noise_generator_test.cc).
constexpr double kZigguratR = 3.6541528853610088;

ZigguratTables MakeZigguratTables() {
  ZigguratTables t;
  const int n = ZigguratTables::kLayers;
  const double r = kZigguratR;
  const double f_r = std::exp(-0.5 * r * r);
  // Area of each strip: the rectangle [0, r] x [0, f(r)] plus the tail, int_r^inf f(x) dx =
  // sqrt(pi / 2) erfc(r / sqrt(2)).
  const double v = r * f_r + std::sqrt(kPi / 2.0) * std::erfc(r / std::sqrt(2.0));
  t.r = r;
  t.x[0] = v / f_r;
  t.f[0] = 0.0;  // Unused: strip 0 is handled by the tail sampler.
  t.x[1] = r;
  t.f[1] = f_r;
  for (int i = 1; i < n - 1; ++i) {
    // f(x[i+1]) = f(x[i]) + v / x[i]  =>  x[i+1] = sqrt(-2 log(f(x[i]) + v / x[i])).
    const double f_next = t.f[i] + v / t.x[i];
    t.f[i + 1] = f_next;
    t.x[i + 1] = std::sqrt(-2.0 * std::log(f_next));
  }
  t.x[n] = 0.0;
  t.f[n] = 1.0;
  for (int i = 0; i < n; ++i) t.ratio[i] = t.x[i + 1] / t.x[i];
  return t;
}

}  // namespace

const ZigguratTables& GetZigguratTables() {
  static const ZigguratTables tables = MakeZigguratTables();
  return tables;
}

}  // namespace internal

double GaussianSampler::NextSlow(int layer, double u) {
  while (true) {
    if (layer == 0) {
      // The tail beyond r [Marsaglia00, section 4; Marsaglia 1964]: with a = -log(U1) / r and
      // b = -log(U2), accept r + a when 2 b > a^2. The sign is that of u.
      double a = 0.0;
      double b = 0.0;
      do {
        a = -std::log(NextUniform()) / tables_.r;
        b = -std::log(NextUniform());
      } while (2.0 * b <= a * a);
      return u < 0.0 ? -(tables_.r + a) : tables_.r + a;
    }
    // Strip i >= 1 beyond its inner rectangle: x in [x[i+1], x[i]); accept when a uniform height
    // between f(x[i]) and f(x[i+1]) falls under the curve.
    const double x = u * tables_.x[layer];
    const double y = tables_.f[layer] + NextUniform() * (tables_.f[layer + 1] - tables_.f[layer]);
    if (y < std::exp(-0.5 * x * x)) return x;
    // Rejected: a whole new draw (the fast path again, written out here).
    const uint32_t bits = NextBits();
    layer = static_cast<int>(bits & 0xff);
    u = static_cast<double>(static_cast<int32_t>(bits) >> 8) * 0x1.0p-23;
    if (std::abs(u) < tables_.ratio[layer]) return u * tables_.x[layer];
  }
}

namespace {

double CheckedDensity(double value, const char* name) {
  if (!std::isfinite(value) || value < 0.0) {
    throw Error(std::string("IMU noise: ") + name + " must be finite and >= 0, got " +
                std::to_string(value));
  }
  return value;
}

}  // namespace

ImuNoiseGenerator::ImuNoiseGenerator(const ImuNoise& noise,
                                     const Eigen::Vector3d& gyro_bias,
                                     const Eigen::Vector3d& accel_bias,
                                     uint64_t seed)
    : gaussian_(seed), gyro_bias_(gyro_bias), accel_bias_(accel_bias) {
  const double f = noise.update_rate_hz;
  if (!std::isfinite(f) || f <= 0.0) {
    throw Error("IMU noise: update_rate must be finite and > 0 Hz, got " + std::to_string(f));
  }
  if (!gyro_bias.allFinite() || !accel_bias.allFinite()) {
    throw Error("IMU noise: initial biases must be finite");
  }
  // [Kalibr]: white noise std sigma * sqrt(f); random-walk step std sigma_rw / sqrt(f).
  CheckedDensity(noise.gyroscope_noise_density, "gyroscope_noise_density");
  CheckedDensity(noise.accelerometer_noise_density, "accelerometer_noise_density");
  CheckedDensity(noise.gyroscope_random_walk, "gyroscope_random_walk");
  CheckedDensity(noise.accelerometer_random_walk, "accelerometer_random_walk");
  gyro_white_std_ = noise.GyroWhiteStd(f);
  accel_white_std_ = noise.AccelWhiteStd(f);
  gyro_step_std_ = noise.GyroRandomWalkStepStd(f);
  accel_step_std_ = noise.AccelRandomWalkStepStd(f);
}

}  // namespace splinecal
