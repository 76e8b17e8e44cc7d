// The IMU measurement model on the spline: predicted gyro and accelerometer readings, and their
// analytic Jacobians with respect to the segment's control poses.
//
// [CONVENTIONS "IMU model"], [seed000 eqs. (9)-(10)], [Lovegrove13 §4]:
//
//     gyro  = w_s(t) + b_g                                  [rad/s]
//     accel = R_w_s(t)^T (a_w(t) - g_w) + b_a               [m/s^2]   (specific force)
//
// with w_s the body angular velocity and a_w = d2p_w_s/dt2 from spline/segment.h, and g_w the
// gravity vector in the world frame, (0, 0, -g) for a gravity-aligned world (GravityWorld). A
// level IMU at rest reads accel = (0, 0, +g). (The seed writes R^T (s'' + g_w) with g_w pointing
// up: the same model.) Noise terms n_g, n_a are not part of the prediction.
//
// Jacobians (RIGHT perturbation of control poses, P_k Exp(d), d = [rho; phi]; local support, see
// spline/segment_jacobians.h for the derivation):
//     d gyro / d P_k   = d w_s / d P_k                    (translation columns zero)
//     d accel / d P_k  = d a_s / d P_k - [R^T g_w]x d phi_T / d P_k,   a_s = R^T a_w
//     d gyro / d b_g = I,   d accel / d b_a = I,   d accel / d g_w = -R_w_s^T.
//
// Trajectory model (spline/trajectory_model.h). The functions without a model are the coupled
// SE(3) spline's; those with a TrajectoryModel first (and those on an SE3Spline, which carries
// its model) follow it. The gyro is the same in both models. The split model's accelerometer
// Jacobian has a trivial position part (spline/split_segment_jacobians.h, step 4):
//     d accel / d rho_k = Bddot_k R_w_s^T R_k,   d accel / d phi_k = [R^T (a_w - g_w)]x
//     dphi_T/dphi_k.
#ifndef SPLINECAL_IMU_IMU_MODEL_H_
#define SPLINECAL_IMU_IMU_MODEL_H_

#include <Eigen/Core>

#include "splinecal/lie/types.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/split_segment.h"
#include "splinecal/spline/split_segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// Standard gravity used unless the user sets another value [m/s^2] (docs/conventions.md "IMU
// model").
inline constexpr double kDefaultGravity = 9.81;

// g_w = (0, 0, -g): gravity in a z-up, gravity-aligned world frame.
template <typename T = double>
Vector3<T> GravityWorld(double g = kDefaultGravity) {
  return Vector3<T>(T(0.0), T(0.0), T(-g));
}

// Predicted gyro and accelerometer readings at `segment` under `model` (either output may be
// nullptr). Templated (double or ceres::Jet): usable inside automatic-differentiation cost
// functions.
template <typename T>
void PredictImu(TrajectoryModel model,
                const SegmentKnots<T>& knots,
                const Segment<T>& segment,
                const Vector3<T>& g_w,
                const Vector3<T>& b_g,
                const Vector3<T>& b_a,
                internal::NonDeducedT<Vector3<T>>* gyro,
                internal::NonDeducedT<Vector3<T>>* accel) {
  Vector3<T> w_s;
  Vector3<T> a_s;
  Matrix3<T> R_w_s;
  internal::EvaluateSegmentBody(model,
                                knots,
                                segment,
                                nullptr,
                                accel != nullptr ? &R_w_s : nullptr,
                                gyro != nullptr ? &w_s : nullptr,
                                nullptr,
                                nullptr,
                                accel != nullptr ? &a_s : nullptr);
  if (gyro != nullptr) *gyro = w_s + b_g;
  if (accel != nullptr) *accel = a_s - R_w_s.transpose() * g_w + b_a;
}

// The same on the coupled SE(3) spline.
template <typename T>
void PredictImu(const SegmentKnots<T>& knots,
                const Segment<T>& segment,
                const Vector3<T>& g_w,
                const Vector3<T>& b_g,
                const Vector3<T>& b_a,
                internal::NonDeducedT<Vector3<T>>* gyro,
                internal::NonDeducedT<Vector3<T>>* accel) {
  PredictImu(TrajectoryModel::kSE3, knots, segment, g_w, b_g, b_a, gyro, accel);
}

template <typename T>
void PredictImu(const SE3Spline<T>& spline,
                const Segment<T>& segment,
                const Vector3<T>& g_w,
                const Vector3<T>& b_g,
                const Vector3<T>& b_a,
                internal::NonDeducedT<Vector3<T>>* gyro,
                internal::NonDeducedT<Vector3<T>>* accel) {
  PredictImu(spline.model(), spline.Knots(segment), segment, g_w, b_g, b_a, gyro, accel);
}

// Gyro prediction w_s + b_g and its Jacobian w.r.t. the segment's control poses (3x6 blocks;
// translation columns are zero). The bias Jacobian is the identity. J may be nullptr.
inline void PredictGyroWithJacobian(const SegmentKnots<double>& knots,
                                    const Segment<double>& segment,
                                    const Eigen::Vector3d& b_g,
                                    Eigen::Vector3d* gyro,
                                    ControlPoseJacobian<3>* J_gyro_ctrl) {
  Eigen::Vector3d w_s;
  EvaluateAngularVelocityJacobian(knots, segment, &w_s, J_gyro_ctrl);
  if (gyro != nullptr) *gyro = w_s + b_g;
}

// Accelerometer prediction R_w_s^T (a_w - g_w) + b_a and its Jacobians w.r.t. the segment's
// control poses (3x6 blocks) and, if J_accel_gw is not null, w.r.t. g_w (= -R_w_s^T). The bias
// Jacobian is the identity. J_accel_ctrl may be nullptr.
inline void PredictAccelWithJacobian(const SegmentKnots<double>& knots,
                                     const Segment<double>& segment,
                                     const Eigen::Vector3d& g_w,
                                     const Eigen::Vector3d& b_a,
                                     Eigen::Vector3d* accel,
                                     ControlPoseJacobian<3>* J_accel_ctrl,
                                     Eigen::Matrix3d* J_accel_gw = nullptr) {
  internal::TraceRequest request = internal::FullTraceRequest();
  request.q_coefficients = J_accel_ctrl != nullptr;
  internal::SegmentTrace<double> trace;
  internal::ForwardPass(knots, segment, request, &trace);
  const Eigen::Vector3d a_s = trace.av[2] + trace.w[2].cross(trace.v[2]);
  // With J_accel_gw the rotation matrix is needed anyway: rotate g_w with it (one product)
  // instead of the four matrix-vector products of RotateToBody.
  Eigen::Vector3d g_s;
  if (J_accel_gw != nullptr) {
    const Eigen::Matrix3d R_s_w = internal::SegmentRotation(knots, trace).transpose();
    g_s.noalias() = R_s_w * g_w;
    *J_accel_gw = -R_s_w;
  } else {
    g_s = internal::RotateToBody(knots, trace, g_w);
  }
  if (accel != nullptr) *accel = a_s - g_s + b_a;
  if (J_accel_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  internal::SpecificForceJacobian(knots, segment, trace, g_s, J_accel_ctrl);
}

// The split SO(3) x R^3 spline's accelerometer prediction R_w_s^T (a_w - g_w) + b_a with the
// Jacobians of PredictAccelWithJacobian (the same tangent and layout). Only the rotations go
// through the forward pass; the control-pose Jacobian is the position weights times
// R_w_s^T R_k and [f]x times the orientation's Jacobian (internal::SplitSpecificForce).
inline void PredictSplitAccelWithJacobian(const SegmentKnots<double>& knots,
                                          const Segment<double>& segment,
                                          const Eigen::Vector3d& g_w,
                                          const Eigen::Vector3d& b_a,
                                          Eigen::Vector3d* accel,
                                          ControlPoseJacobian<3>* J_accel_ctrl,
                                          Eigen::Matrix3d* J_accel_gw = nullptr) {
  internal::SegmentTrace<double> trace;
  internal::SplitForwardPass(knots, segment, false, false, &trace);
  Eigen::Vector3d f;
  internal::SplitSpecificForce(knots, segment, trace, g_w, &f, J_accel_ctrl, J_accel_gw);
  if (J_accel_gw != nullptr) *J_accel_gw = -*J_accel_gw;  // d accel / d g_w = -R_w_s^T
  if (accel != nullptr) *accel = f + b_a;
}

// PredictAccelWithJacobian or PredictSplitAccelWithJacobian.
inline void PredictAccelWithJacobian(TrajectoryModel model,
                                     const SegmentKnots<double>& knots,
                                     const Segment<double>& segment,
                                     const Eigen::Vector3d& g_w,
                                     const Eigen::Vector3d& b_a,
                                     Eigen::Vector3d* accel,
                                     ControlPoseJacobian<3>* J_accel_ctrl,
                                     Eigen::Matrix3d* J_accel_gw = nullptr) {
  if (model == TrajectoryModel::kSplitSO3R3) {
    PredictSplitAccelWithJacobian(knots, segment, g_w, b_a, accel, J_accel_ctrl, J_accel_gw);
    return;
  }
  PredictAccelWithJacobian(knots, segment, g_w, b_a, accel, J_accel_ctrl, J_accel_gw);
}

// The same on an SE3Spline<double> (the accelerometer follows spline.model()).
inline void PredictGyroWithJacobian(const SE3Spline<double>& spline,
                                    const Segment<double>& segment,
                                    const Eigen::Vector3d& b_g,
                                    Eigen::Vector3d* gyro,
                                    ControlPoseJacobian<3>* J_gyro_ctrl) {
  PredictGyroWithJacobian(spline.Knots(segment), segment, b_g, gyro, J_gyro_ctrl);
}

inline void PredictAccelWithJacobian(const SE3Spline<double>& spline,
                                     const Segment<double>& segment,
                                     const Eigen::Vector3d& g_w,
                                     const Eigen::Vector3d& b_a,
                                     Eigen::Vector3d* accel,
                                     ControlPoseJacobian<3>* J_accel_ctrl,
                                     Eigen::Matrix3d* J_accel_gw = nullptr) {
  PredictAccelWithJacobian(
      spline.model(), spline.Knots(segment), segment, g_w, b_a, accel, J_accel_ctrl, J_accel_gw);
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_MODEL_H_
