// Lines of a fixed log-log slope through confidence intervals: the geometry behind every noise-
// term decision of allan/noise_fit.h.
//
// Each averaging time tau_i of an Allan deviation curve carries an interval [low_i, high_i] of the
// true deviation (allan/edf.h). On log-log axes, with l_i = ln tau_i, a line of slope s,
// ln adev = c + s l, passes through every interval of the points first..last exactly when
//
//     max_i (ln low_i - s l_i)  <=  c  <=  min_i (ln high_i - s l_i),
//
// so "the curve follows slope s over [tau_first, tau_last]" is this intersection being non-empty,
// and "the curve there tells slope s from slope s'" is the intersection for s' being empty. Both
// need no assumption about how the points correlate: they use each point's own interval.
//
// Feasibility is monotone: a line through the intervals of a window passes through those of any
// sub-window. So the windows to examine are the maximal ones, [a, b(a)] with b(a) the last point
// a line still fits from a; b(a) never decreases with a, and all of them are found in one sweep.
#ifndef SPLINECAL_ALLAN_SLOPE_LINES_H_
#define SPLINECAL_ALLAN_SLOPE_LINES_H_

#include <vector>

namespace splinecal {

// One point of a curve in natural logarithms.
struct LogPoint {
  double log_tau = 0.0;
  double log_adev = 0.0;
  double log_low = 0.0;   // ln of the interval's low end
  double log_high = 0.0;  // ln of the interval's high end
  double weight = 1.0;    // for the least-squares intercept: 1 / variance of log_adev
};

// Points first..last, inclusive.
struct PointWindow {
  int first = 0;
  int last = -1;
  int size() const { return last - first + 1; }
};

// The intercepts c of the lines of slope `slope` that pass through every interval of `window`:
// [*c_low, *c_high]. Returns false (and leaves the outputs alone) when there is none.
bool LineFitsWindow(const std::vector<LogPoint>& points,
                    PointWindow window,
                    double slope,
                    double* c_low = nullptr,
                    double* c_high = nullptr);

// The maximal windows of at least min_points points, among the points begin..end - 1, through
// whose intervals a line of `slope` passes; at most one per start point, in order of start.
std::vector<PointWindow> MaximalLineWindows(
    const std::vector<LogPoint>& points, int begin, int end, double slope, int min_points);

// The weighted least-squares intercept of a line of `slope` through the points of the window
// (the weighted mean of log_adev - slope * log_tau), clamped into [c_low, c_high].
double WeightedIntercept(const std::vector<LogPoint>& points,
                         PointWindow window,
                         double slope,
                         double c_low,
                         double c_high);

// The weighted least-squares slope of log_adev against log_tau over the window (at least two
// distinct taus): the curve's measured slope.
double MeasuredSlope(const std::vector<LogPoint>& points, PointWindow window);

// Span of the window in decades of tau.
double SpanDecades(const std::vector<LogPoint>& points, PointWindow window);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_SLOPE_LINES_H_
