// IMU noise parameters in Kalibr's continuous-time densities (docs/conventions.md, "IMU model").
//
// At sample rate f, white noise has a per-sample standard deviation of sigma * sqrt(f), and the
// bias random walk a per-sample step of sigma_rw / sqrt(f) [Kalibr].
#ifndef SPLINECAL_IMU_NOISE_H_
#define SPLINECAL_IMU_NOISE_H_

#include <cmath>

namespace splinecal {

struct ImuNoise {
  double gyroscope_noise_density = 1.6968e-4;      // [rad/s/sqrt(Hz)]
  double gyroscope_random_walk = 1.9393e-5;        // [rad/s^2/sqrt(Hz)]
  double accelerometer_noise_density = 2.0e-3;     // [m/s^2/sqrt(Hz)]
  double accelerometer_random_walk = 3.0e-3;       // [m/s^3/sqrt(Hz)]
  double update_rate_hz = 200.0;                   // [Hz]

  // The defaults above are the EuRoC ADIS16448 values (its sensor.yaml).
  static ImuNoise Adis16448() { return ImuNoise(); }

  // Per-sample standard deviations at rate f [Hz] (docs/conventions.md, "IMU model"): white noise
  // density * sqrt(f), random-walk step density / sqrt(f).
  double GyroWhiteStd(double rate_hz) const { return gyroscope_noise_density * std::sqrt(rate_hz); }
  double AccelWhiteStd(double rate_hz) const {
    return accelerometer_noise_density * std::sqrt(rate_hz);
  }
  double GyroRandomWalkStepStd(double rate_hz) const {
    return gyroscope_random_walk / std::sqrt(rate_hz);
  }
  double AccelRandomWalkStepStd(double rate_hz) const {
    return accelerometer_random_walk / std::sqrt(rate_hz);
  }
};

}  // namespace splinecal

#endif  // SPLINECAL_IMU_NOISE_H_
