// The sample rate of an IMU recording, from its timestamps (robust to dropped samples).
#ifndef SPLINECAL_IMU_IMU_RATE_H_
#define SPLINECAL_IMU_IMU_RATE_H_

#include <cstdint>
#include <vector>

#include "splinecal/imu/imu_sample.h"

namespace splinecal {

// The median of the differences of consecutive times [ns]; 0 for fewer than 2 times.
int64_t MedianPeriodNs(const std::vector<int64_t>& times_ns);

// 1 / the median sample period [Hz]; 0 for fewer than 2 samples.
double ImuRateHz(const std::vector<ImuSample>& imu);

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_RATE_H_
