// The median of a sample, the one robust centre every area uses (pixel noise by the median
// absolute deviation, a typical frame period, the medoid's spread).
#ifndef SPLINECAL_MEDIAN_H_
#define SPLINECAL_MEDIAN_H_

#include <algorithm>
#include <vector>

namespace splinecal {

// The upper median (the element at size/2 in sorted order) of `values`; 0 when empty.
// O(n) by partial sorting of the copy.
inline double Median(std::vector<double> values) {
  if (values.empty()) return 0.0;
  const auto mid = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), mid, values.end());
  return *mid;
}

}  // namespace splinecal

#endif  // SPLINECAL_MEDIAN_H_
