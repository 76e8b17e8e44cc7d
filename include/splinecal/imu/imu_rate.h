// The sample rate of an IMU recording, from its timestamps (robust to dropped samples).
#ifndef SPLINECAL_IMU_IMU_RATE_H_
#define SPLINECAL_IMU_IMU_RATE_H_

#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"

namespace splinecal {

// The median of the differences of consecutive times [ns]; 0 for fewer than 2 times.
int64_t MedianPeriodNs(const std::vector<int64_t>& times_ns);

// 1 / the median sample period [Hz]; 0 for fewer than 2 samples.
double ImuRateHz(const std::vector<ImuSample>& imu);

// The sample rates of real IMUs: MEMS parts run at 100 Hz to a few kHz (EuRoC's ADIS16448 200 Hz,
// a phone 100-500 Hz, a tactical-grade unit up to 2-4 kHz). A rate outside this range computed
// from int64-nanosecond timestamps means the timestamps are in another unit (microseconds give
// 1000 times the rate) or the file is not an IMU stream at its own rate; every result would be
// wrong (Kalibr's update_rate, the noise densities, the spline's knots).
constexpr double kMinImuRateHz = 10.0;
constexpr double kMaxImuRateHz = 10000.0;

// Throws splinecal::Error "source: ..." when rate_hz is outside [kMinImuRateHz, kMaxImuRateHz].
// from_timestamps: the rate comes from timestamps read as nanoseconds, and the message names the
// unit they look like and the fix; else it was given (allan's --rate) and must be in Hz. Every
// IMU reader calls it (io/euroc.h, io/static_recording.h) and so do the Python bindings' array
// paths.
void CheckImuRate(double rate_hz, const std::string& source, bool from_timestamps = true);

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_RATE_H_
