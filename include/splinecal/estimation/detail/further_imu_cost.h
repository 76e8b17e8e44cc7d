// The residuals of a further IMU of a rig (every IMU after the first, the reference whose frame
// the spline T_w_b(t) is): its gyro and accelerometer readings predicted from the spline's motion
// at its mounting point through its own Kalibr model (docs/calibrate.md, "Several IMUs";
// docs/imu_models.md, "A further IMU with a model"), with analytic Jacobians.
//
// A reading stamped t (the further IMU's clock) senses the motion at t + time_offset on the
// reference clock (Kalibr's IccImu: tk = stamp + timeOffset; imu/imu_intrinsics.h). With the
// spline's body motion (w_b, dw_b, f_b) there (imu/rigid_body_point.h), the readings are
// imu/imu_intrinsic_model.h's PredictImuReadings with this IMU's C_i_b, r_b and, for
// `scale-misalignment` and `scale-misalignment-size-effect`, its own M_a, M_g, A, C_gyro_i (and
// ry_i, rz_i): Kalibr's IccSensors.py with T_i_b = (C_i_b, -C_i_b r_b). `calibrated`:
//
//   gyro  = C_i_b w_b + b_g(t)                                          [rad/s]
//   accel = C_i_b (f_b + dw_b x r_b + w_b x (w_b x r_b)) + b_a(t)       [m/s^2]
//
// residuals (predicted - measured) / sigma per axis, 6 per sample (gyro, then accel), every
// sample of one spline segment stacked. b_g, b_a are this IMU's own constant biases or bias
// spline (estimation/bias_costs.h) on the reference spline's layout.
//
// Jacobians: the spline's motion and its control-pose Jacobians (estimation/detail/
// imu_model_motion.h) chained through the model's (imu/imu_intrinsic_model.h); C_i_b moves as
// C_i_b Exp(dphi) and its ambient quaternion Jacobian is d/dphi times the SO3Manifold's Minus
// Jacobian (as the pose blocks, estimation/detail/pose_block_jacobian.h); C_gyro_i = Exp(phi)
// as in imu_model_costs.h. The time offset's column, d pred / du / dt, needs the spline's third
// derivative (angular jerk in dw_b): it is computed by forward-mode differentiation in u alone
// (one dual number through the same templated prediction), exact like the rest.
//
// The segment of each sample is chosen when the problem is built, from the time offset then; the
// time offset moves u = (t + time_offset - t_i) / dt within the segment's cubic polynomial, which
// continues smoothly beyond [0, 1): the caller rebuilds its residuals when the offset has moved
// by more than a fraction of dt (src/calib/further_imus.h). The bias weights are taken at the
// stamp plus that offset (a bias spline changes by far less than its noise over milliseconds).
//
// Parameter blocks, in this order (FurtherImuBlockIndex):
//   4 control poses (7 each, lie/se3_manifold.h), bias_blocks gyro-bias points (3 each),
//   bias_blocks accel-bias points (3 each), g_w (3), q_i_b (4: C_i_b, {qx, qy, qz, qw}, SO3Manifold),
//   r_b (3: the IMU's origin in the reference IMU's frame b [m]), time_offset (1 [s]),
//   then for scale-misalignment[-size-effect]: m_a (6), m_g (6), a (9), phi_gyro_i (3)
//   (estimation/imu_model_parameters.h's layouts), and for the size effect ry_i (3), rz_i (3).
#ifndef SPLINECAL_ESTIMATION_DETAIL_FURTHER_IMU_COST_H_
#define SPLINECAL_ESTIMATION_DETAIL_FURTHER_IMU_COST_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <array>
#include <vector>

#include "splinecal/estimation/detail/imu_model_intrinsics.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// One reading of the further IMU inside a segment.
struct FurtherImuSample {
  double u0 = 0.0;  // (stamp - t_i) / dt: u at time offset 0
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();
  std::array<double, 4> bias_weights = {1.0, 0.0, 0.0, 0.0};
};

// The readings of one spline segment and what they share.
struct FurtherImuSegment {
  int segment_index = 1;  // i: control poses i-1 .. i+2
  double dt_s = 0.0;      // knot spacing [s]
  TrajectoryModel model = TrajectoryModel::kSE3;
  ImuModelKind kind = ImuModelKind::kCalibrated;  // this IMU's model
  double sigma_gyro = 1.0;   // per-sample white-noise std [rad/s]
  double sigma_accel = 1.0;  // [m/s^2]
  int bias_blocks = 1;       // 1 (constant biases) or 4 (a bias spline's segment)
  std::vector<FurtherImuSample> samples;
};

// The blocks' indices (the file comment's order) for nb bias points per block list.
struct FurtherImuBlockIndex {
  explicit FurtherImuBlockIndex(int nb)
      : gyro_bias(4), accel_bias(4 + nb), gravity(4 + 2 * nb), q_i_b(5 + 2 * nb),
        r_b(6 + 2 * nb), time_offset(7 + 2 * nb), m_a(8 + 2 * nb), m_g(9 + 2 * nb),
        a(10 + 2 * nb), phi_gyro_i(11 + 2 * nb), ry_i(12 + 2 * nb), rz_i(13 + 2 * nb) {}
  int gyro_bias, accel_bias, gravity, q_i_b, r_b, time_offset;
  int m_a, m_g, a, phi_gyro_i, ry_i, rz_i;  // only for the models that have them
};

// The IMU's intrinsics from its blocks (all of the cost's blocks, in order), the parameters its
// model does not have at nominal. Templated (double or ceres::Jet).
template <typename T>
ImuIntrinsics<T> FurtherImuIntrinsics(ImuModelKind kind, int nb, T const* const* blocks) {
  const FurtherImuBlockIndex b(nb);
  ImuIntrinsics<T> p;
  if (kind != ImuModelKind::kCalibrated) {
    const T zero[3] = {T(0.0), T(0.0), T(0.0)};
    const bool size_effect = kind == ImuModelKind::kScaleMisalignmentSizeEffect;
    p = ImuModelParameters::Intrinsics<T>(blocks[b.m_a],
                                          blocks[b.m_g],
                                          blocks[b.a],
                                          blocks[b.phi_gyro_i],
                                          size_effect ? blocks[b.ry_i] : zero,
                                          size_effect ? blocks[b.rz_i] : zero);
  }
  p.C_i_b = RotationFromBlock(blocks[b.q_i_b]).matrix();
  p.r_b = Eigen::Map<const Vector3<T>>(blocks[b.r_b]);
  return p;
}

// The predicted readings of one sample at u (its segment's parameter) for the knots, gravity,
// intrinsics and biases given: the residuals' model in the scalar type T.
template <typename T>
void PredictFurtherImuAt(const FurtherImuSegment& s,
                         const SegmentKnotData<T>& data,
                         const T& u,
                         const Vector3<T>& g_w,
                         const ImuIntrinsics<T>& p,
                         const Vector3<T>& b_g,
                         const Vector3<T>& b_a,
                         Vector3<T>* gyro,
                         Vector3<T>* accel) {
  const Segment<T> seg = MakeSegment(s.segment_index, u, s.dt_s);
  BodyMotion<T> motion;
  Matrix3<T> R_w_b;
  Vector3<T> a_b;
  internal::EvaluateSegmentBody(
      s.model, data.knots(), seg, nullptr, &R_w_b, &motion.w_b, &motion.dw_b, nullptr, &a_b);
  motion.f_b = a_b - R_w_b.transpose() * g_w;
  PredictImuReadings<T>(s.kind, p, motion, b_g, b_a, gyro, accel);
}

// The stacked residuals (6 rows per sample); the caller owns the result and passes the blocks in
// the order of the file comment.
ceres::CostFunction* NewFurtherImuCost(const FurtherImuSegment& segment);

// The predicted readings at one sample for given block values (the blocks as above): the
// residuals' model in plain doubles, for statistics after a solve.
void PredictFurtherImu(const FurtherImuSegment& segment,
                       const FurtherImuSample& sample,
                       double const* const* blocks,
                       Eigen::Vector3d* gyro,
                       Eigen::Vector3d* accel);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_FURTHER_IMU_COST_H_
