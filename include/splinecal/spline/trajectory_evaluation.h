// Evaluation by trajectory model (spline/trajectory_model.h): the functions of spline/segment.h
// and spline/segment_jacobians.h with a TrajectoryModel first, which run the coupled SE(3)
// spline's or the split SO(3) x R^3 spline's version (spline/split_segment.h,
// spline/split_segment_jacobians.h) on the same segment and knot caches. Callers that hold a
// model at run time (SE3Spline, the cost functions of estimation/) use these; the model-specific
// functions stay available for code that knows its model.
//
// The body angular velocity and its Jacobian are the same in both models
// (EvaluateAngularVelocityJacobian has no model argument).
#ifndef SPLINECAL_SPLINE_TRAJECTORY_EVALUATION_H_
#define SPLINECAL_SPLINE_TRAJECTORY_EVALUATION_H_

#include <Eigen/Core>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/types.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/split_segment.h"
#include "splinecal/spline/split_segment_jacobians.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

namespace internal {

// EvaluateSegmentBody (spline/segment.h) or EvaluateSplitSegmentBody (spline/split_segment.h).
template <typename T>
void EvaluateSegmentBody(TrajectoryModel model,
                         const SegmentKnots<T>& knots,
                         const Segment<T>& segment,
                         NonDeducedT<SE3<T>>* T_w_s,
                         NonDeducedT<Matrix3<T>>* R_w_s,
                         NonDeducedT<Vector3<T>>* w_s,
                         NonDeducedT<Vector3<T>>* w_dot_s,
                         NonDeducedT<Vector3<T>>* v_s,
                         NonDeducedT<Vector3<T>>* a_s) {
  if (model == TrajectoryModel::kSplitSO3R3) {
    EvaluateSplitSegmentBody(knots, segment, T_w_s, R_w_s, w_s, w_dot_s, v_s, a_s);
    return;
  }
  EvaluateSegmentBody(knots, segment, T_w_s, R_w_s, w_s, w_dot_s, v_s, a_s);
}

}  // namespace internal

// EvaluateSegment or EvaluateSplitSegment: pose, body angular velocity and acceleration, world
// linear velocity and acceleration, each optional.
template <typename T>
void EvaluateSegment(TrajectoryModel model,
                     const SegmentKnots<T>& knots,
                     const Segment<T>& segment,
                     internal::NonDeducedT<SE3<T>>* T_w_s,
                     internal::NonDeducedT<Vector3<T>>* w_s = nullptr,
                     internal::NonDeducedT<Vector3<T>>* w_dot_s = nullptr,
                     internal::NonDeducedT<Vector3<T>>* v_w = nullptr,
                     internal::NonDeducedT<Vector3<T>>* a_w = nullptr) {
  if (model == TrajectoryModel::kSplitSO3R3) {
    EvaluateSplitSegment(knots, segment, T_w_s, w_s, w_dot_s, v_w, a_w);
    return;
  }
  EvaluateSegment(knots, segment, T_w_s, w_s, w_dot_s, v_w, a_w);
}

// EvaluatePoseJacobian or EvaluateSplitPoseJacobian (double; knots with Jacobian caches).
inline void EvaluatePoseJacobian(TrajectoryModel model,
                                 const SegmentKnots<double>& knots,
                                 const Segment<double>& segment,
                                 SE3d* T_w_s,
                                 ControlPoseJacobian<6>* J_pose_ctrl) {
  if (model == TrajectoryModel::kSplitSO3R3) {
    EvaluateSplitPoseJacobian(knots, segment, T_w_s, J_pose_ctrl);
    return;
  }
  EvaluatePoseJacobian(knots, segment, T_w_s, J_pose_ctrl);
}

// EvaluateLinearAccelerationJacobian or EvaluateSplitLinearAccelerationJacobian.
inline void EvaluateLinearAccelerationJacobian(TrajectoryModel model,
                                               const SegmentKnots<double>& knots,
                                               const Segment<double>& segment,
                                               Eigen::Vector3d* a_w,
                                               ControlPoseJacobian<3>* J_aw_ctrl) {
  if (model == TrajectoryModel::kSplitSO3R3) {
    EvaluateSplitLinearAccelerationJacobian(knots, segment, a_w, J_aw_ctrl);
    return;
  }
  EvaluateLinearAccelerationJacobian(knots, segment, a_w, J_aw_ctrl);
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_TRAJECTORY_EVALUATION_H_
