#include "splinecal/plot/plot_decimation.h"

#include <algorithm>

namespace splinecal {
namespace plot {

std::vector<size_t> DecimatedIndices(size_t n, int max_points, bool keep_last) {
  std::vector<size_t> indices;
  if (n == 0) return indices;
  const size_t max_kept = static_cast<size_t>(std::max(1, max_points));
  const size_t stride = std::max<size_t>(1, (n + max_kept - 1) / max_kept);
  indices.reserve(n / stride + 2);
  for (size_t i = 0; i < n; i += stride) indices.push_back(i);
  if (keep_last && indices.back() != n - 1) indices.push_back(n - 1);
  return indices;
}

}  // namespace plot
}  // namespace splinecal
