// KnotLayout: where the knots of a uniform spline lie in time, and the one segment lookup that
// every user of a spline shares (SE3Spline, the bias spline, the residuals of estimation/).
//
//   Knot times t_i = t0 + i dt, i = 0..n-1 (n = num_control_poses >= 4). A cubic segment i
//   (i = 1..n-3) covers [t_i, t_{i+1}] and depends on control poses i-1 .. i+2
//   ([CONVENTIONS "The spline"]). Valid times are [t_1, t_{n-2}]; the end t_{n-2} belongs to the
//   last segment at u = 1.
//
// Time is int64 nanoseconds (absolute) or double seconds since t0 (relative; what the cost
// functions see, and what a ceres::Jet time offset is added to). Both lookups give the same
// segment for the same instant.
#ifndef SPLINECAL_SPLINE_KNOT_LAYOUT_H_
#define SPLINECAL_SPLINE_KNOT_LAYOUT_H_

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "splinecal/spline/basis.h"

namespace splinecal {

// Relative times within this fraction of a segment (1e-9 dt: below a nanosecond for dt < 1 s)
// outside [t_1, t_{n-2}] are snapped onto the end: (n-2) dt computed in double can round a few
// ulps past it.
inline constexpr double kEndSnapSegments = 1e-9;

// A time's place in the spline: segment index i (1..n-3) and u = (t - t_i) / dt in [0, 1].
struct SegmentPosition {
  int index = 1;
  double u = 0.0;
};

// Control poses first_index .. first_index + num_poses - 1 of a spline.
struct ControlPoseWindow {
  int first_index = 0;
  int num_poses = 0;
  int last_index() const { return first_index + num_poses - 1; }
};

struct KnotLayout {
  int64_t t0_ns = 0;
  int64_t dt_ns = 0;
  int num_control_poses = 0;

  double dt_s() const { return 1e-9 * static_cast<double>(dt_ns); }
  int64_t knot_time_ns(int i) const { return t0_ns + static_cast<int64_t>(i) * dt_ns; }
  // The valid range [t_1, t_{n-2}], absolute [ns] and relative to t0 [s].
  int64_t start_time_ns() const { return knot_time_ns(1); }
  int64_t end_time_ns() const { return knot_time_ns(num_control_poses - 2); }
  double start_time() const { return dt_s(); }
  double end_time() const { return TimeSinceT0(end_time_ns()); }
  double TimeSinceT0(int64_t t_ns) const { return 1e-9 * static_cast<double>(t_ns - t0_ns); }
  bool valid() const { return num_control_poses >= kSplineOrder && dt_ns > 0; }

  // The segment of an absolute time, in exact integer arithmetic. False outside [t_1, t_{n-2}].
  bool SegmentAtNs(int64_t t_ns, SegmentPosition* position) const {
    if (!valid() || t_ns < start_time_ns() || t_ns > end_time_ns()) return false;
    const int64_t since_t0 = t_ns - t0_ns;
    int index = static_cast<int>(since_t0 / dt_ns);
    int64_t remainder = since_t0 % dt_ns;
    if (index > num_control_poses - 3) {  // t_ns == t_{n-2}: the last segment at u = 1
      index = num_control_poses - 3;
      remainder = dt_ns;
    }
    position->index = index;
    position->u = static_cast<double>(remainder) / static_cast<double>(dt_ns);
    return true;
  }

  // The segment of a time in seconds since t0. False outside [t_1, t_{n-2}] (kEndSnapSegments
  // of slack at both ends) and for NaN.
  bool SegmentAt(double t_s, SegmentPosition* position) const {
    if (!valid()) return false;
    const double s = t_s / dt_s();  // time in units of dt since t0
    const double last = static_cast<double>(num_control_poses - 2);
    if (!(s >= 1.0 - kEndSnapSegments && s <= last + kEndSnapSegments)) return false;
    const int index = std::clamp(static_cast<int>(std::floor(s)), 1, num_control_poses - 3);
    position->index = index;
    position->u = std::clamp(s - static_cast<double>(index), 0.0, 1.0);
    return true;
  }

  // The segment index of a time clamped into the valid range: SegmentAt / SegmentAtNs of the
  // nearest valid time (for attaching a residual whose time may still move, e.g. with an
  // estimated time offset, and for a spline evaluated a little past its ends). 1 for NaN.
  int ClampedSegmentAt(double t_s) const {
    SegmentPosition position;
    SegmentAt(std::clamp(t_s, start_time(), end_time()), &position);
    return position.index;
  }
  int ClampedSegmentAtNs(int64_t t_ns) const {
    SegmentPosition position;
    SegmentAtNs(std::clamp(t_ns, start_time_ns(), end_time_ns()), &position);
    return position.index;
  }

  // The smallest window of control poses whose segments cover every time in [t_lo_s, t_hi_s]
  // (seconds since t0). False when the interval is empty or not inside the valid range.
  bool WindowCovering(double t_lo_s, double t_hi_s, ControlPoseWindow* window) const {
    SegmentPosition lo;
    SegmentPosition hi;
    if (!(t_lo_s <= t_hi_s) || !SegmentAt(t_lo_s, &lo) || !SegmentAt(t_hi_s, &hi)) return false;
    window->first_index = lo.index - 1;
    window->num_poses = hi.index + 2 - (lo.index - 1) + 1;
    return true;
  }
};

// The smallest layout with spacing dt_ns whose valid range [t_1, t_{n-2}] covers
// [start_ns, end_ns]: t_1 = start_ns (so t0 = start_ns - dt_ns) and
// n = ceil((end_ns - start_ns) / dt_ns) + 3. Throws splinecal::Error if dt_ns <= 0,
// end_ns < start_ns, or the layout would need more than 1e8 knot intervals.
KnotLayout KnotLayoutCovering(int64_t start_ns, int64_t end_ns, int64_t dt_ns);

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_KNOT_LAYOUT_H_
