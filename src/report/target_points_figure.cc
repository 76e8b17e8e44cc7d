#include "splinecal/report/target_points_figure.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// The largest of 1, 2, 5 times a power of ten not above x (x > 0).
double RoundDown125(double x) {
  const double decade = std::pow(10.0, std::floor(std::log10(x)));
  for (double m : {5.0, 2.0, 1.0}) {
    if (m * decade <= x) return m * decade;
  }
  return decade;
}

}  // namespace

plot::Figure TargetPointsFigure(const TargetDeformationResult& d) {
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  Eigen::Vector2d low = Eigen::Vector2d::Constant(1e300), high = -low;
  double longest = 0.0;
  for (const auto& [id, p] : d.refined_target.points) {
    low = low.cwiseMin(p.head<2>());
    high = high.cwiseMax(p.head<2>());
  }
  for (const auto& [id, c] : d.point_offsets_m) longest = std::max(longest, c.head<2>().norm());
  const double width = std::max((high - low).maxCoeff(), 1e-9);
  const double gain = longest > 0.0 ? RoundDown125(0.05 * width / longest) : 1.0;

  plot::Figure figure;
  figure.columns = 2;
  figure.title = "Target points: the data's positions against the file's";
  plot::Panel& plane = plot::AddPanel(
      &figure, StringPrintf("offsets in the plane, x %g", gain), "target x [m]", "target y [m]");
  plane.equal_aspect = true;
  plane.legend = plot::LegendPosition::kNone;
  plot::Series& points = plane.series.emplace_back();
  points.line = false;
  points.marker = plot::Marker::kCircle;
  points.marker_size = 1.5;
  points.color = "#777777";
  plot::Series& arrows = plane.series.emplace_back();
  arrows.color = "#000000";
  arrows.line_width = 1.4;
  plot::Panel& normal = plot::AddPanel(
      &figure, "offsets along the normal", "target x [m]", "offset along z [mm]");
  normal.legend = plot::LegendPosition::kNone;
  plot::Series& heights = normal.series.emplace_back();
  heights.line = false;
  heights.marker = plot::Marker::kCircle;
  for (const auto& [id, p] : d.refined_target.points) {
    const auto offset = d.point_offsets_m.find(id);
    const Eigen::Vector3d c =
        offset != d.point_offsets_m.end() ? offset->second : Eigen::Vector3d::Zero();
    const Eigen::Vector3d file = p - c;  // the refined point is the file's plus its offset
    points.x.push_back(file.x());
    points.y.push_back(file.y());
    if (offset == d.point_offsets_m.end()) continue;
    // Each arrow a segment of a broken line (NaN between).
    for (const double s : {0.0, gain}) {
      arrows.x.push_back(file.x() + s * c.x());
      arrows.y.push_back(file.y() + s * c.y());
    }
    arrows.x.push_back(kNaN);
    arrows.y.push_back(kNaN);
    heights.x.push_back(file.x());
    heights.y.push_back(1e3 * c.z());
    const auto std = d.point_offsets_std_m.find(id);
    const double s = std != d.point_offsets_std_m.end() ? 1e3 * std->second.z() : 0.0;
    heights.y_low.push_back(1e3 * c.z() - s);
    heights.y_high.push_back(1e3 * c.z() + s);
  }
  return figure;
}

plot::Figure TargetPointsFigure(const TargetPointsCheck& check) {
  TargetDeformationResult d;
  d.shape.kind = TargetDeformationKind::kPoints;
  for (const auto& [id, p] : check.file_points_m) {
    d.refined_target.points[id] = p + check.offsets_m.at(id);
  }
  d.point_offsets_m = check.offsets_m;
  d.point_offsets_std_m = check.offsets_std_m;
  plot::Figure figure = TargetPointsFigure(d);
  figure.title = "Target points: one step from the file's layout (poses and intrinsics held)";
  return figure;
}

}  // namespace splinecal
