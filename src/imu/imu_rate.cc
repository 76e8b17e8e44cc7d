#include "splinecal/imu/imu_rate.h"

#include <algorithm>

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

}  // namespace splinecal
