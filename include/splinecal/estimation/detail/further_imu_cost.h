// The residuals of a further IMU of a rig (every IMU after the first, the reference whose frame
// the spline T_w_b(t) is): its gyro and accelerometer readings predicted from the spline's motion
// at its mounting point, differentiated by Ceres' automatic differentiation (correctness first;
// docs/calibrate.md, "Several IMUs").
//
// A reading stamped t (the further IMU's clock) senses the motion at t + time_offset on the
// reference clock (Kalibr's IccImu: tk = stamp + timeOffset; imu/imu_intrinsics.h). With the
// spline's body motion (w_b, dw_b, f_b) there (imu/rigid_body_point.h, imu/spline_body_motion.h),
// Kalibr's `calibrated` model (imu/imu_intrinsic_model.h, IccSensors.py):
//
//   gyro  = C_i_b w_b + b_g(t)                                          [rad/s]
//   accel = C_i_b (f_b + dw_b x r_b + w_b x (w_b x r_b)) + b_a(t)       [m/s^2]
//
// residuals (predicted - measured) / sigma per axis, 6 per sample (gyro, then accel), every
// sample of one spline segment stacked. b_g, b_a are this IMU's own constant biases or bias
// spline (estimation/bias_costs.h) on the reference spline's layout.
//
// The segment of each sample is chosen when the problem is built, from the time offset then; the
// time offset moves u = (t + time_offset - t_i) / dt within the segment's cubic polynomial, which
// continues smoothly beyond [0, 1): the caller rebuilds its residuals when the offset has moved
// by more than a fraction of dt (src/calib/further_imus.h). The bias weights are taken at the
// stamp plus that offset (a bias spline changes by far less than its noise over milliseconds).
//
// Parameter blocks, in this order:
//   4 control poses (7 each, lie/se3_manifold.h), bias_blocks gyro-bias points (3 each),
//   bias_blocks accel-bias points (3 each), g_w (3), q_i_b (4: C_i_b, {qx, qy, qz, qw}, SO3Manifold),
//   r_b (3: the IMU's origin in the reference IMU's frame b [m]), time_offset (1 [s]).
#ifndef SPLINECAL_ESTIMATION_DETAIL_FURTHER_IMU_COST_H_
#define SPLINECAL_ESTIMATION_DETAIL_FURTHER_IMU_COST_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <array>
#include <vector>

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
  double sigma_gyro = 1.0;   // per-sample white-noise std [rad/s]
  double sigma_accel = 1.0;  // [m/s^2]
  int bias_blocks = 1;       // 1 (constant biases) or 4 (a bias spline's segment)
  std::vector<FurtherImuSample> samples;
};

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
