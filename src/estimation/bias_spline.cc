#include "splinecal/estimation/bias_spline.h"

#include <algorithm>
#include <cmath>

namespace splinecal {

BiasSpline::BiasSpline(BiasModel model, const KnotLayout& pose_layout, double bias_knot_spacing_s)
    : model_(model) {
  if (model_ == BiasModel::kConstant) return;
  pose_knots_per_bias_knot_ =
      std::max(1, static_cast<int>(std::lround(bias_knot_spacing_s / pose_layout.dt_s())));
  const int64_t dt_ns = static_cast<int64_t>(pose_knots_per_bias_knot_) * pose_layout.dt_ns;
  const int64_t span = pose_layout.end_time_ns() - pose_layout.start_time_ns();
  layout_.dt_ns = dt_ns;
  layout_.t0_ns = pose_layout.start_time_ns() - dt_ns;
  layout_.num_control_poses = static_cast<int>(span / dt_ns + (span % dt_ns != 0 ? 1 : 0)) + 3;
}

int BiasSpline::SegmentOfPoseSegment(int pose_segment) const {
  if (is_constant()) return 0;
  return std::clamp(1 + (pose_segment - 1) / pose_knots_per_bias_knot_, 1, num_points() - 3);
}

BiasWeights BiasSpline::WeightsInSegment(int64_t t_ns, int segment) const {
  BiasWeights w;
  if (is_constant()) return w;
  const int64_t tb = layout_.knot_time_ns(segment);
  const double u =
      std::clamp(static_cast<double>(t_ns - tb) / static_cast<double>(layout_.dt_ns), 0.0, 1.0);
  w.first_point = segment - 1;
  w.weights = BiasSplineWeights(u);
  return w;
}

BiasWeights BiasSpline::WeightsAt(int64_t t_ns) const {
  if (is_constant()) return BiasWeights();
  return WeightsInSegment(t_ns, layout_.ClampedSegmentAtNs(t_ns));
}

Eigen::Vector3d BiasSpline::Evaluate(const double* values, int64_t t_ns) const {
  if (is_constant()) return Eigen::Map<const Eigen::Vector3d>(values);
  const BiasWeights w = WeightsAt(t_ns);
  Eigen::Vector3d b = Eigen::Vector3d::Zero();
  for (int j = 0; j < 4; ++j) {
    b += w.weights[j] * Eigen::Map<const Eigen::Vector3d>(values + 3 * (w.first_point + j));
  }
  return b;
}

}  // namespace splinecal
