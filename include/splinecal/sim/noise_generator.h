// Seeded IMU noise in Kalibr's continuous-time model (docs/conventions.md, "IMU model").
//
// A reading at sample k of a sensor with white-noise density sigma and random-walk density
// sigma_rw, sampled at f [Hz], is
//
//     reading_k = truth_k + b_k + n_k,     n_k ~ N(0, (sigma sqrt(f))^2)          (white noise)
//     b_0 = initial bias,   b_k = b_{k-1} + w_k,   w_k ~ N(0, (sigma_rw / sqrt(f))^2)   (k >= 1)
//
// so that Var(b_k - b_0) = sigma_rw^2 * k / f = sigma_rw^2 * T after T = k / f seconds [Kalibr].
//
// Normal draws come from a 64-bit Mersenne Twister (std::mt19937_64, whose output sequence the
// C++ standard fixes) turned into N(0, 1) by our own ziggurat [Marsaglia00]: the same seed gives
// the same doubles on every run and every platform with IEEE doubles and a correctly rounded
// sqrt (the table uses exp/log, computed once; they are the only libm dependence). Each 64-bit
// engine word feeds two draws (GaussianSampler::Next); 12 draws per IMU sample (white noise
// and random-walk steps of both sensors) cost ~60 ns here (bench/imu_bench.cc).
//
// References: [Kalibr] Kalibr wiki, "IMU Noise Model"; [Marsaglia00] G. Marsaglia, W. W. Tsang,
// "The ziggurat method for generating random variables", J. Stat. Software 5(8), 2000.
#ifndef SPLINECAL_SIM_NOISE_GENERATOR_H_
#define SPLINECAL_SIM_NOISE_GENERATOR_H_

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <random>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"

namespace splinecal {

namespace internal {

// Ziggurat tables for the unnormalised density f(x) = exp(-x^2 / 2), x >= 0, cut into
// kZigguratLayers strips of equal area v [Marsaglia00, section 2]:
//   x[0] = v / f(r) (the base strip, a rectangle of height f(r) plus the tail beyond r, seen as
//   a rectangle of the same area), x[1] = r, f(x[i+1]) = f(x[i]) + v / x[i], x[kLayers] = 0.
// ratio[i] = x[i+1] / x[i]: a draw |u| < ratio[i] lies inside the part of strip i that is
// entirely under the curve and is accepted without evaluating f.
struct ZigguratTables {
  static constexpr int kLayers = 256;
  std::array<double, kLayers + 1> x;
  std::array<double, kLayers + 1> f;  // f(x[i])
  std::array<double, kLayers> ratio;
  double r;
};
const ZigguratTables& GetZigguratTables();

}  // namespace internal

// Standard normal N(0, 1) draws, reproducible from a 64-bit seed.
class GaussianSampler {
 public:
  explicit GaussianSampler(uint64_t seed) : engine_(seed), tables_(internal::GetZigguratTables()) {}

  // One N(0, 1) draw. Each 64-bit engine word feeds two draws (low 32 bits first). In a 32-bit
  // half, bits 0-7 pick the strip and bits 8-31 (a signed 24-bit integer) the abscissa
  // u in [-1, 1): the values are quantised to 2^-23 of a strip width (below 5e-7 standard
  // deviations), far under anything an IMU simulation can see. The fast path (~99% of draws)
  // is a table lookup and a multiply.
  double Next() {
    const uint32_t bits = NextBits();
    const int layer = static_cast<int>(bits & 0xff);
    const double u = static_cast<double>(static_cast<int32_t>(bits) >> 8) * 0x1.0p-23;
    if (std::abs(u) < tables_.ratio[layer]) return u * tables_.x[layer];
    return NextSlow(layer, u);
  }

  // A uniform draw in (0, 1] with 53 random bits (never 0, so log() is finite).
  double NextUniform() { return static_cast<double>((engine_() >> 11) + 1) * 0x1.0p-53; }

  std::mt19937_64& engine() { return engine_; }

 private:
  uint32_t NextBits() {
    if (has_spare_) {
      has_spare_ = false;
      return spare_;
    }
    const uint64_t word = engine_();
    spare_ = static_cast<uint32_t>(word >> 32);
    has_spare_ = true;
    return static_cast<uint32_t>(word);
  }

  // The rejection part: the tail beyond r for strip 0, the curved edge for the others.
  double NextSlow(int layer, double u);

  std::mt19937_64 engine_;
  const internal::ZigguratTables& tables_;
  uint32_t spare_ = 0;
  bool has_spare_ = false;
};

// White noise and bias random walk for one IMU (gyro and accelerometer), per axis independent.
class ImuNoiseGenerator {
 public:
  // noise: densities and noise.update_rate_hz, the sample rate f. gyro_bias / accel_bias: b_0.
  // Throws splinecal::Error if the rate is not positive and finite or a density is negative or
  // not finite.
  ImuNoiseGenerator(const ImuNoise& noise,
                    const Eigen::Vector3d& gyro_bias,
                    const Eigen::Vector3d& accel_bias,
                    uint64_t seed);

  // Corrupts one true reading: adds the bias of this sample and white noise. The first call uses
  // the initial biases; every later call first takes one random-walk step. Writes the biases that
  // were added (the true biases of this sample) to gyro_bias / accel_bias unless nullptr.
  // Draw order (fixed, part of the reproducibility contract): bias steps gyro xyz, accel xyz
  // (skipped on the first call), then white noise gyro xyz, accel xyz.
  void Corrupt(ImuSample* sample, Eigen::Vector3d* gyro_bias, Eigen::Vector3d* accel_bias) {
    if (started_) {
      for (int i = 0; i < 3; ++i) gyro_bias_[i] += gyro_step_std_ * gaussian_.Next();
      for (int i = 0; i < 3; ++i) accel_bias_[i] += accel_step_std_ * gaussian_.Next();
    }
    started_ = true;
    for (int i = 0; i < 3; ++i) {
      sample->gyro[i] += gyro_bias_[i] + gyro_white_std_ * gaussian_.Next();
    }
    for (int i = 0; i < 3; ++i) {
      sample->accel[i] += accel_bias_[i] + accel_white_std_ * gaussian_.Next();
    }
    if (gyro_bias != nullptr) *gyro_bias = gyro_bias_;
    if (accel_bias != nullptr) *accel_bias = accel_bias_;
  }

 private:
  GaussianSampler gaussian_;
  double gyro_white_std_;
  double accel_white_std_;
  double gyro_step_std_;
  double accel_step_std_;
  Eigen::Vector3d gyro_bias_;
  Eigen::Vector3d accel_bias_;
  bool started_ = false;
};

}  // namespace splinecal

#endif  // SPLINECAL_SIM_NOISE_GENERATOR_H_
