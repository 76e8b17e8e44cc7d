#include "splinecal/allan/slope_lines.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace splinecal {

bool LineFitsWindow(const std::vector<LogPoint>& points,
                    PointWindow window,
                    double slope,
                    double* c_low,
                    double* c_high) {
  CHECK_GE(window.first, 0);
  CHECK_LT(window.last, static_cast<int>(points.size()));
  double low = -std::numeric_limits<double>::infinity();
  double high = std::numeric_limits<double>::infinity();
  for (int i = window.first; i <= window.last; ++i) {
    low = std::max(low, points[i].log_low - slope * points[i].log_tau);
    high = std::min(high, points[i].log_high - slope * points[i].log_tau);
    if (low > high) return false;
  }
  if (c_low != nullptr) *c_low = low;
  if (c_high != nullptr) *c_high = high;
  return true;
}

std::vector<PointWindow> MaximalLineWindows(
    const std::vector<LogPoint>& points, int begin, int end, double slope, int min_points) {
  std::vector<PointWindow> windows;
  int last = begin - 1;  // b(a): the window [a, last] fits; never decreases with a
  int previous_last = begin - 2;
  for (int a = begin; a < end; ++a) {
    last = std::max(last, a);  // a single point always fits
    while (last + 1 < end && LineFitsWindow(points, {a, last + 1}, slope)) ++last;
    // [a, last] is maximal unless the window of the previous start reached as far (then it
    // contains this one).
    if (last > previous_last && last - a + 1 >= min_points) windows.push_back({a, last});
    previous_last = std::max(previous_last, last);
  }
  return windows;
}

double WeightedIntercept(const std::vector<LogPoint>& points,
                         PointWindow window,
                         double slope,
                         double c_low,
                         double c_high) {
  double sum = 0.0;
  double weights = 0.0;
  for (int i = window.first; i <= window.last; ++i) {
    sum += points[i].weight * (points[i].log_adev - slope * points[i].log_tau);
    weights += points[i].weight;
  }
  return std::clamp(sum / weights, c_low, c_high);
}

double MeasuredSlope(const std::vector<LogPoint>& points, PointWindow window) {
  double w = 0.0, wx = 0.0, wy = 0.0;
  for (int i = window.first; i <= window.last; ++i) {
    w += points[i].weight;
    wx += points[i].weight * points[i].log_tau;
    wy += points[i].weight * points[i].log_adev;
  }
  const double x_mean = wx / w;
  const double y_mean = wy / w;
  double sxx = 0.0, sxy = 0.0;
  for (int i = window.first; i <= window.last; ++i) {
    const double dx = points[i].log_tau - x_mean;
    sxx += points[i].weight * dx * dx;
    sxy += points[i].weight * dx * (points[i].log_adev - y_mean);
  }
  return sxx > 0.0 ? sxy / sxx : std::numeric_limits<double>::quiet_NaN();
}

double SpanDecades(const std::vector<LogPoint>& points, PointWindow window) {
  return (points[window.last].log_tau - points[window.first].log_tau) / std::log(10.0);
}

}  // namespace splinecal
