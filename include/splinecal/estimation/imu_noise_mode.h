// How an estimate treats the IMU noise densities it is given (estimation/imu_noise_estimate.h
// says what each mode does and why the default does not re-weight the white noise).
#ifndef SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_
#define SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_

#include <array>
#include <string>

#include "splinecal/enum_names.h"

namespace splinecal {

enum class ImuNoiseMode {
  kGiven,       // the given densities weight the solve and the covariance (imu.yaml trusted)
  kEstimated,   // random walks re-estimated; white noise measured for the covariance (default)
  kReweighted,  // as kEstimated, and the measured white noise also re-weights the solve
};

// The --imu-noise values, the default first.
inline constexpr std::array<EnumName<ImuNoiseMode>, 3> kImuNoiseModeNames = {{
    {ImuNoiseMode::kEstimated, "estimated"},
    {ImuNoiseMode::kReweighted, "reweighted"},
    {ImuNoiseMode::kGiven, "given"},
}};

inline std::string ImuNoiseModeName(ImuNoiseMode mode) {
  return NameOf(kImuNoiseModeNames, mode);
}

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_NOISE_MODE_H_
