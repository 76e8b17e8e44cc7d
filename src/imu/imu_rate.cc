#include "splinecal/imu/imu_rate.h"

#include <algorithm>
#include <cmath>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {

int64_t MedianPeriodNs(const std::vector<int64_t>& times_ns) {
  std::vector<int64_t> periods;
  periods.reserve(times_ns.size());
  for (size_t k = 1; k < times_ns.size(); ++k) periods.push_back(times_ns[k] - times_ns[k - 1]);
  if (periods.empty()) return 0;
  std::nth_element(periods.begin(), periods.begin() + periods.size() / 2, periods.end());
  return periods[periods.size() / 2];
}

double ImuRateHz(const std::vector<ImuSample>& imu) {
  std::vector<int64_t> times(imu.size());
  for (size_t k = 0; k < imu.size(); ++k) times[k] = imu[k].t_ns;
  const int64_t period = MedianPeriodNs(times);
  return period > 0 ? 1e9 / static_cast<double>(period) : 0.0;
}

void CheckImuRate(double rate_hz, const std::string& source, bool from_timestamps) {
  auto in_range = [](double hz) { return hz >= kMinImuRateHz && hz <= kMaxImuRateHz; };
  if (in_range(rate_hz)) return;
  std::string cause;
  if (!from_timestamps) {
    cause = "give the sample rate in Hz";
  } else if (!std::isfinite(rate_hz) || rate_hz <= 0.0) {
    cause = "the timestamps do not advance";
  } else if (rate_hz > kMaxImuRateHz) {
    // Timestamps in a coarser unit read as nanoseconds give the rate times 10^3, 10^6, 10^9.
    static const struct {
      double factor;
      const char* unit;
    } kUnits[] = {{1e3, "microseconds"}, {1e6, "milliseconds"}, {1e9, "seconds"}};
    for (const auto& unit : kUnits) {
      if (!in_range(rate_hz / unit.factor)) continue;
      cause = StringPrintf("the timestamps look like %s (then the IMU runs at %.6g Hz); they must "
                           "be int64 nanoseconds: multiply them by %.0f",
                           unit.unit,
                           rate_hz / unit.factor,
                           unit.factor);
      break;
    }
    if (cause.empty()) cause = "the timestamps are not int64 nanoseconds of one IMU stream";
  } else {
    cause = "too slow for an IMU: a decimated file, or timestamps in a unit finer than nanoseconds";
  }
  throw Error(StringPrintf("%s: IMU sample rate %.6g Hz%s is outside %g Hz .. %g kHz: %s",
                           source.c_str(),
                           rate_hz,
                           from_timestamps ? " from the timestamps" : "",
                           kMinImuRateHz,
                           kMaxImuRateHz / 1000.0,
                           cause.c_str()));
}

}  // namespace splinecal
