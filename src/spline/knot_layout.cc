#include "splinecal/spline/knot_layout.h"

#include <string>

#include "splinecal/error.h"

namespace splinecal {

KnotLayout KnotLayoutCovering(int64_t start_ns, int64_t end_ns, int64_t dt_ns) {
  if (dt_ns <= 0) {
    throw Error("knot spacing must be > 0, got " + std::to_string(dt_ns) + " ns");
  }
  if (end_ns < start_ns) {
    throw Error("knot layout: end " + std::to_string(end_ns) + " ns is before start " +
                std::to_string(start_ns) + " ns");
  }
  const int64_t span_ns = end_ns - start_ns;
  const int64_t intervals = span_ns / dt_ns + (span_ns % dt_ns != 0 ? 1 : 0);
  if (intervals > 100'000'000) {
    throw Error("knot layout: " + std::to_string(intervals) +
                " knot intervals is too many (increase the knot spacing)");
  }
  KnotLayout layout;
  layout.t0_ns = start_ns - dt_ns;
  layout.dt_ns = dt_ns;
  layout.num_control_poses = static_cast<int>(intervals) + 3;
  return layout;
}

}  // namespace splinecal
