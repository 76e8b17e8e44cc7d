// One segment of the split SO(3) x R^3 spline (TrajectoryModel::kSplitSO3R3,
// spline/trajectory_model.h): the pose and its time derivatives in one pass, on the same segment
// lookup (Segment) and knot caches (SegmentKnots) as the coupled SE(3) spline of spline/segment.h.
//
// The model ([Sommer20] §3-4; the position spline of basalt-headers and Kalibr). For t in
// [t_i, t_{i+1}), u = (t - t_i) / dt, and the segment's control poses P_j = (R_j, p_j),
// j = 0..3 (T_{i-1}..T_{i+2}), with the cumulative coefficients b_j = Bt_j(u) of spline/basis.h:
//
//     R_w_s(t) = R_0 A_1 A_2 A_3,      A_j = Exp(b_j phi_j),   phi_j = Log(R_{j-1}^T R_j)
//     p_w_s(t) = sum_{j=0..3} B_j(u) p_j = p_0 + sum_{j=1..3} b_j dp_j,   dp_j = p_j - p_{j-1}
//
// (B_j = Bt_j - Bt_{j+1}, spline/basis.h BasisFromCumulative.) The rotation is the rotation part
// of the coupled spline exactly: phi_j is KnotDelta::phi, A_j's rotation is computed by the same
// internal::ComputeScaledExp, and the orientation, body angular velocity w_s and angular
// acceleration w_dot_s come from the same forward pass (spline/segment.h, internal::ForwardPass
// without its translation part), so the two models agree on them to the last bit. The position
// is linear in the control positions, so its time derivatives only differentiate the weights:
//
//     v_w = dp_w_s/dt = sum_j bdot_j dp_j,      a_w = d2p_w_s/dt2 = sum_j bddot_j dp_j,
//     v_s = R_w_s^T v_w,                         a_s = R_w_s^T a_w
//
// with bdot_j, bddot_j the time derivatives of Bt_j (Segment::b_dot, b_ddot). Unlike the coupled
// spline, a_w depends on no rotation: that is what makes the accelerometer's Jacobian cheap
// (spline/split_segment_jacobians.h).
//
// Scalar type: templates on T (double or ceres::Jet<double, N>); the time offset u may be a Jet.
#ifndef SPLINECAL_SPLINE_SPLIT_SEGMENT_H_
#define SPLINECAL_SPLINE_SPLIT_SEGMENT_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"
#include "splinecal/spline/basis.h"
#include "splinecal/spline/segment.h"

namespace splinecal {
namespace internal {

// sum_{j=1..3} weights_j dp_j: p_w_s(t) - p_0 with weights = b, v_w with b_dot, a_w with b_ddot.
template <typename T>
Vector3<T> BlendPositionSteps(const SegmentKnots<T>& knots,
                              const Eigen::Matrix<T, kSplineOrder, 1>& weights) {
  return weights[1] * knots.deltas[0].dp + weights[2] * knots.deltas[1].dp +
         weights[3] * knots.deltas[2].dp;
}

// The rotation part of the forward pass (no translations, no linear rates): the A_j, and w_s,
// w_dot_s when asked for.
template <typename T>
void SplitForwardPass(const SegmentKnots<T>& knots,
                      const Segment<T>& segment,
                      bool rates,
                      bool angular_acceleration,
                      SegmentTrace<T>* trace) {
  TraceRequest request;
  request.rates = rates || angular_acceleration;
  request.acceleration = angular_acceleration;
  ForwardPass(knots, segment, request, trace);
}

// T_w_s = (R_0 A_1 A_2 A_3, p_0 + sum_j b_j dp_j).
template <typename T>
SE3<T> SplitSegmentPose(const SegmentKnots<T>& knots,
                        const Segment<T>& segment,
                        const SegmentTrace<T>& trace) {
  return SE3<T>(SO3<T>(SegmentQuaternion(knots, trace)),
                knots.T_first->translation() + BlendPositionSteps(knots, segment.b));
}

// The body-frame form of every output, as internal::EvaluateSegmentBody of spline/segment.h
// (nullptr = not wanted, skipped): T_w_s, R_w_s, w_s, w_dot_s, v_s = R_w_s^T dp_w_s/dt,
// a_s = R_w_s^T d2p_w_s/dt2.
template <typename T>
void EvaluateSplitSegmentBody(const SegmentKnots<T>& knots,
                              const Segment<T>& segment,
                              NonDeducedT<SE3<T>>* T_w_s,
                              NonDeducedT<Matrix3<T>>* R_w_s,
                              NonDeducedT<Vector3<T>>* w_s,
                              NonDeducedT<Vector3<T>>* w_dot_s,
                              NonDeducedT<Vector3<T>>* v_s,
                              NonDeducedT<Vector3<T>>* a_s) {
  SegmentTrace<T> trace;
  SplitForwardPass(knots, segment, w_s != nullptr, w_dot_s != nullptr, &trace);
  if (T_w_s != nullptr) *T_w_s = SplitSegmentPose(knots, segment, trace);
  if (w_s != nullptr) *w_s = trace.w[2];
  if (w_dot_s != nullptr) *w_dot_s = trace.aw[2];
  if (R_w_s == nullptr && v_s == nullptr && a_s == nullptr) return;
  const Matrix3<T> R = SegmentRotation(knots, trace);
  if (R_w_s != nullptr) *R_w_s = R;
  if (v_s != nullptr) *v_s = R.transpose() * BlendPositionSteps(knots, segment.b_dot);
  if (a_s != nullptr) *a_s = R.transpose() * BlendPositionSteps(knots, segment.b_ddot);
}

}  // namespace internal

// Evaluates the split spline's segment at `segment` in one pass; the outputs of EvaluateSegment
// (spline/segment.h), every one optional (nullptr = not wanted, its work skipped):
//   T_w_s    pose of the IMU/body frame s in the world w
//   w_s      body angular velocity vee(R_w_s^T dR_w_s/dt)            [rad/s]
//   w_dot_s  body angular acceleration dw_s/dt                       [rad/s^2]
//   v_w      world linear velocity dp_w_s/dt                         [m/s]
//   a_w      world linear acceleration d2p_w_s/dt2                   [m/s^2]
// The world rates need no rotation at all (header comment).
template <typename T>
void EvaluateSplitSegment(const SegmentKnots<T>& knots,
                          const Segment<T>& segment,
                          internal::NonDeducedT<SE3<T>>* T_w_s,
                          internal::NonDeducedT<Vector3<T>>* w_s = nullptr,
                          internal::NonDeducedT<Vector3<T>>* w_dot_s = nullptr,
                          internal::NonDeducedT<Vector3<T>>* v_w = nullptr,
                          internal::NonDeducedT<Vector3<T>>* a_w = nullptr) {
  if (T_w_s != nullptr || w_s != nullptr || w_dot_s != nullptr) {
    internal::EvaluateSplitSegmentBody(
        knots, segment, T_w_s, nullptr, w_s, w_dot_s, nullptr, nullptr);
  }
  if (v_w != nullptr) *v_w = internal::BlendPositionSteps(knots, segment.b_dot);
  if (a_w != nullptr) *a_w = internal::BlendPositionSteps(knots, segment.b_ddot);
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_SPLIT_SEGMENT_H_
