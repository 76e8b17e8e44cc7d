// The spline's body motion at one IMU sample with its Jacobians w.r.t. the segment's control
// poses, and the chain rule through an IMU model's Jacobians w.r.t. that motion: what the
// analytic IMU-model costs share (estimation/detail/imu_model_costs.h for the reference IMU,
// estimation/detail/further_imu_cost.h for the further ones).
//
//     d pred / d P_k = J_w d w_b / d P_k + J_dw d dw_b / d P_k + J_f d f_b / d P_k
//
// w_b: spline/segment_jacobians.h step 4; dw_b: spline/angular_acceleration_jacobian.h;
// f_b = R_w_b^T (a_w - g_w): segment_jacobians.h step 5 (imu/imu_model.h).
#ifndef SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_MOTION_H_
#define SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_MOTION_H_

#include <Eigen/Core>
#include <array>

#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/spline/angular_acceleration_jacobian.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace internal {

// The spline's motion at one sample: w_b, dw_b and f_b = R_w_b^T (a_w - g_w) with, on request,
// d f_b / d control poses (right tangent), and d f_b / d g_w = -R_w_b^T.
struct SampleMotion {
  BodyMotion<double> motion;
  SegmentTrace<double> angular;  // the SO(3) forward pass (rates, acceleration)
  ControlPoseJacobian<3> J_f;
  Eigen::Matrix3d J_f_gw;
};

inline void EvaluateSampleMotion(TrajectoryModel model,
                                 const SegmentKnots<double>& knots,
                                 const Segment<double>& seg,
                                 const Eigen::Vector3d& g_w,
                                 bool f_pose_jacobian,
                                 SampleMotion* m) {
  PredictAccelWithJacobian(model,
                           knots,
                           seg,
                           g_w,
                           Eigen::Vector3d::Zero(),
                           &m->motion.f_b,
                           f_pose_jacobian ? &m->J_f : nullptr,
                           &m->J_f_gw);
  TraceRequest request;
  request.rates = true;
  request.acceleration = true;
  ForwardPass(knots, seg, request, &m->angular);
  m->motion.w_b = m->angular.w[2];
  m->motion.dw_b = m->angular.aw[2];
}

// d prediction / d control pose k (kRows x 6, right tangent) = J_w J_w_k + J_dw J_dw_k +
// J_f J_f_k for a prediction of kRows rows, every term whose model Jacobian is exactly zero
// skipped (r_b = 0 zeroes the accelerometer's w_b and dw_b without the size effect; A = 0 the
// gyro's f_b).
template <int kRows>
void ChainPoseJacobians(const SegmentKnots<double>& knots,
                        const Segment<double>& seg,
                        const SampleMotion& m,
                        const Eigen::Matrix<double, kRows, 3>& J_w,
                        const Eigen::Matrix<double, kRows, 3>& J_dw,
                        const Eigen::Matrix<double, kRows, 3>& J_f,
                        std::array<Eigen::Matrix<double, kRows, 6>, kSplineOrder>* out) {
  const bool use_w = !J_w.isZero(0.0);
  const bool use_dw = !J_dw.isZero(0.0);
  const bool use_f = !J_f.isZero(0.0);
  ControlPoseJacobian<3> J_ws;
  ControlPoseJacobian<3> J_dws;
  if (use_w) EvaluateAngularVelocityJacobian(knots, seg, nullptr, &J_ws);
  if (use_dw) AngularAccelerationJacobian(knots, seg, m.angular, &J_dws);
  for (int k = 0; k < kSplineOrder; ++k) {
    Eigen::Matrix<double, kRows, 6>& J = (*out)[k];
    if (use_f) {
      J.noalias() = J_f * m.J_f.blocks[k];
    } else {
      J.setZero();
    }
    // The angular blocks' translation columns are zero.
    if (use_w) J.template rightCols<3>().noalias() += J_w * J_ws.blocks[k].template rightCols<3>();
    if (use_dw) {
      J.template rightCols<3>().noalias() += J_dw * J_dws.blocks[k].template rightCols<3>();
    }
  }
}

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_MOTION_H_
