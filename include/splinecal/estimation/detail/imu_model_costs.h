// The IMU residuals of one spline segment under Kalibr's scale-misalignment models
// (imu/imu_intrinsic_model.h, docs/imu_models.md), with analytic Jacobians: the spline's body
// motion at each sample -- w_b (spline/segment_jacobians.h, step 4), dw_b
// (spline/angular_acceleration_jacobian.h; docs/imu_models.md, "Analytic Jacobians") and
// f_b = R_w_b^T (a_w - g_w) (segment_jacobians.h step 5, imu/imu_model.h) -- each with its
// Jacobian w.r.t. the four control poses, goes through PredictImuReadings and its Jacobians
// w.r.t. w_b, dw_b, f_b and the model's parameters, by the chain rule:
//
//     d pred / d P_k = J_w d w_b / d P_k + J_dw d dw_b / d P_k + J_f d f_b / d P_k
//     d pred / d g_w = -J_f R_w_b^T,     d pred / d phi_gyro_i = J_phi Jr(phi_gyro_i)
//
// (C_gyro_i = Exp(phi) moves as C_gyro_i Exp(Jr(phi) dphi)). The pose Jacobians are lifted to
// the ambient blocks as in estimation/detail/imu_costs.h. Their automatic-differentiation twins
// (the tests' oracle) are in tests/testing/autodiff_imu_model_costs.h.
//
// Parameter blocks (ImuModelParameters holds their values):
//   gyro:   4 control poses (7 each), the segment's gyro bias points (3 each), g_w (3; f_b enters
//           through the g-sensitivity A), m_g (6), a (9), phi_gyro_i (3)
//   accel:  4 control poses, the segment's accel bias points, g_w, m_a (6)
//           (+ ry_i (3), rz_i (3) for scale-misalignment-size-effect)
// m_a, m_g, a: imu/matrix_parameters.h's layouts. C_gyro_i = Exp(phi_gyro_i) (a rotation vector
// about the nominal identity: Euclidean, so its standard deviation is in radians per axis). The
// IMU is the reference one (C_i_b = I, r_b = 0: the spline's frame is its accelerometer frame).
#ifndef SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_COSTS_H_
#define SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_COSTS_H_

#include <ceres/cost_function.h>

#include <array>
#include <vector>

#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/imu/imu_model_kind.h"

namespace splinecal {

// The segment's samples and how many bias points each block list carries (1 or 4).
struct ImuModelSegment {
  ImuModelKind kind = ImuModelKind::kScaleMisalignment;
  ImuResidualSegment segment;
  std::vector<ImuResidualSample> samples;
  int bias_blocks = 1;
};

// The gyro or accelerometer residuals (predicted - measured) / sigma, as estimation/imu_costs.h,
// of every sample of the segment; the caller owns the result and passes the blocks in the order
// above.
ceres::CostFunction* NewImuModelGyroCost(const ImuModelSegment& segment);
ceres::CostFunction* NewImuModelAccelCost(const ImuModelSegment& segment);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_COSTS_H_
