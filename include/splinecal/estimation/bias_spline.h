// BiasSpline: where the control points of the IMU bias model lie in time, and their weights at a
// sample (estimation/bias_costs.h has the spline's definition and its random-walk prior).
//
//   Constant (BiasModel::kConstant): one control point; weight 1.
//   Spline (BiasModel::kSpline): control points c_m at tb_m = tb_0 + m db, with db = k dt a whole
//   number k >= 1 of pose knot intervals and tb_1 = t_1, the start of the pose spline's valid
//   range. Bias segment m (points m-1 .. m+2) covers [tb_m, tb_{m+1}]: every pose segment i lies
//   inside bias segment m(i) = 1 + floor((i - 1) / k), so one IMU residual block per pose segment
//   depends on one bias segment.
#ifndef SPLINECAL_ESTIMATION_BIAS_SPLINE_H_
#define SPLINECAL_ESTIMATION_BIAS_SPLINE_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/spline/knot_layout.h"

namespace splinecal {

// The control points a bias sample depends on and their weights.
struct BiasWeights {
  int first_point = 0;  // c_{first} .. c_{first + num - 1}
  std::array<double, 4> weights = {1.0, 0.0, 0.0, 0.0};
};

class BiasSpline {
 public:
  // A constant bias.
  BiasSpline() = default;
  // The bias model over the valid range of `pose_layout`; for kSpline db is bias_knot_spacing_s
  // rounded to a whole number (>= 1) of pose knot intervals.
  BiasSpline(BiasModel model, const KnotLayout& pose_layout, double bias_knot_spacing_s);

  BiasModel model() const { return model_; }
  bool is_constant() const { return model_ == BiasModel::kConstant; }
  int num_points() const { return layout_.num_control_poses; }
  // Control points per residual: 1 (constant) or 4 (one bias segment).
  int points_per_segment() const { return is_constant() ? 1 : 4; }
  int64_t t0_ns() const { return layout_.t0_ns; }  // tb_0 (kSpline)
  int64_t dt_ns() const { return layout_.dt_ns; }  // db (kSpline)
  double dt_s() const { return layout_.dt_s(); }

  // The bias segment of pose segment i (its first control point is the returned index - 1).
  int SegmentOfPoseSegment(int pose_segment) const;
  // Weights at t_ns inside bias segment m (u clamped into [0, 1]).
  BiasWeights WeightsInSegment(int64_t t_ns, int segment) const;
  // Weights at any t_ns in the pose spline's valid range.
  BiasWeights WeightsAt(int64_t t_ns) const;
  // b(t) from control points stored 3 per point in `values`.
  Eigen::Vector3d Evaluate(const double* values, int64_t t_ns) const;

 private:
  BiasModel model_ = BiasModel::kConstant;
  int pose_knots_per_bias_knot_ = 1;
  // The bias control points' knots (kSpline); one point at spacing 1 ns for kConstant.
  KnotLayout layout_{0, 1, 1};
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_BIAS_SPLINE_H_
