// How an estimate treats the IMU noise densities it is given (estimation/imu_noise_estimate.h
// says what each mode does and why the default does not re-weight the white noise).
#ifndef SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_
#define SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_

#include <string>

namespace splinecal {

enum class ImuNoiseMode {
  kGiven,       // the given densities weight the solve and the covariance (imu.yaml trusted)
  kEstimated,   // random walks re-estimated; white noise measured for the covariance (default)
  kReweighted,  // as kEstimated, and the measured white noise also re-weights the solve
};

// "given", "estimated", "reweighted" (the --imu-noise values).
inline std::string ImuNoiseModeName(ImuNoiseMode mode) {
  switch (mode) {
    case ImuNoiseMode::kGiven:
      return "given";
    case ImuNoiseMode::kEstimated:
      return "estimated";
    case ImuNoiseMode::kReweighted:
      return "reweighted";
  }
  return "estimated";
}

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_
