// The spline's body angular acceleration dw_s and its analytic Jacobian with respect to the four
// control poses of a segment (double only), in the tangent and layout of
// spline/segment_jacobians.h (RIGHT perturbation P_k Exp(d), d = [rho; phi]). Kalibr's IMU
// models need it: the size effect reads dw_i x r_k (imu/size_effect_model.h), an IMU away from
// the body origin dw_b x r_b (docs/imu_models.md, "Analytic Jacobians: the angular
// acceleration").
//
// Derivation, continuing step 4 of spline/segment_jacobians.h (the angular velocity) one order
// up. The rates recursion of spline/segment.h on SO(3): dw_1 = bddot_1 phi_1 and, for j = 2, 3,
//
//     w_j  = y_j + bdot_j phi_j,                      y_j = R_j^T w_{j-1}
//     dw_j = z_j + bdot_j y_j x phi_j + bddot_j phi_j, z_j = R_j^T dw_{j-1}
//
// with R_j = Exp(b_j phi_j). A change of phi_j moves R_j^T x by [R_j^T x]x S_j dphi_j,
// S_j = b_j Jr(b_j phi_j), and d(y x phi) = [y]x dphi - [phi]x dy. With H_j = [y_j]x S_j +
// bdot_j I (d w_j / d phi_j) and
//
//     N_j = ([z_j]x - bdot_j [phi_j]x [y_j]x) S_j + bdot_j [y_j]x + bddot_j I   (d dw_j / d phi_j)
//
// the sensitivities of dw_s = dw_3 to the knot rotations phi_1..3 are (w_{j-1} enters dw_j
// through y_j: d dw_j / d w_{j-1} = -bdot_j [phi_j]x R_j^T)
//
//     Ka_3 = N_3
//     Ka_2 = R_3^T N_2 - bdot_3 [phi_3]x R_3^T H_2
//     Ka_1 = bddot_1 R_3^T R_2^T - bdot_1 bdot_2 R_3^T [phi_2]x R_2^T
//            - bdot_1 bdot_3 [phi_3]x R_3^T R_2^T
//
// and, as for w_s (d phi_k = Jr^-1(phi_k) d_k - Jl^-1(phi_k) d_{k-1}, rotation rows only),
//
//     J_dw_k = [0, Ka_k Jr^-1(phi_k) - Ka_{k+1} Jl^-1(phi_{k+1})]   (terms that exist).
//
// The orientation is the SO(3) cumulative spline in both trajectory models
// (spline/trajectory_model.h), so this is the Jacobian of either.
#ifndef SPLINECAL_SPLINE_ANGULAR_ACCELERATION_JACOBIAN_H_
#define SPLINECAL_SPLINE_ANGULAR_ACCELERATION_JACOBIAN_H_

#include <Eigen/Core>
#include <array>

#include "splinecal/lie/so3.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"

namespace splinecal {

namespace internal {

// Ka_1..Ka_3 at [0..2] (header comment). The trace holds the rates and the acceleration.
inline void AngularAccelerationSensitivities(const SegmentKnots<double>& knots,
                                             const Segment<double>& segment,
                                             const SegmentTrace<double>& trace,
                                             std::array<Eigen::Matrix3d, 3>* Ka) {
  const Eigen::Matrix3d R3t = trace.A[2].R.transpose();
  const Eigen::Matrix3d R2t = trace.A[1].R.transpose();
  // N_j, j = 2, 3 (index j - 1).
  const auto N = [&](int index, const Eigen::Matrix3d& S) {
    const double bd = segment.b_dot[index + 1];
    Eigen::Matrix3d out =
        (Hat(trace.zw[index]) - bd * HatHat(knots.deltas[index].phi, trace.yw[index])) * S;
    AddHat(bd, trace.yw[index], &out);
    out.diagonal().array() += segment.b_ddot[index + 1];
    return out;
  };
  Eigen::Matrix3d S3;
  Eigen::Matrix3d S2;
  ScaledRightJacobianSO3(knots.deltas[2], trace.A[2], &S3);
  ScaledRightJacobianSO3(knots.deltas[1], trace.A[1], &S2);
  Eigen::Matrix3d H2 = Hat(trace.yw[1]) * S2;
  H2.diagonal().array() += segment.b_dot[2];
  const Eigen::Vector3d& phi2 = knots.deltas[1].phi;
  const Eigen::Vector3d& phi3 = knots.deltas[2].phi;
  const double bd3 = segment.b_dot[3];
  const Eigen::Matrix3d R32t = R3t * R2t;
  (*Ka)[2] = N(2, S3);
  (*Ka)[1] = R3t * N(1, S2) - bd3 * HatMul(phi3, R3t * H2);
  (*Ka)[0] = segment.b_ddot[1] * R32t -
             (segment.b_dot[1] * segment.b_dot[2]) * (R3t * HatMul(phi2, R2t)) -
             (segment.b_dot[1] * bd3) * HatMul(phi3, R32t);
}

}  // namespace internal

// d dw_s / d(control poses) from a forward pass that holds the rates and the acceleration
// (TraceRequest rates + acceleration, or the full pass): 3x6 blocks whose translation columns
// are zero. Needs the knot Jacobian caches.
inline void AngularAccelerationJacobian(const SegmentKnots<double>& knots,
                                        const Segment<double>& segment,
                                        const internal::SegmentTrace<double>& trace,
                                        ControlPoseJacobian<3>* J_dws_ctrl) {
  internal::CheckJacobianCaches(knots);
  std::array<Eigen::Matrix3d, 3> Ka;
  internal::AngularAccelerationSensitivities(knots, segment, trace, &Ka);
  const KnotDeltaJacobians* K = knots.jacobians;
  J_dws_ctrl->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    Eigen::Matrix<double, 3, 6>& block = J_dws_ctrl->blocks[k];
    block.leftCols<3>().setZero();
    if (k >= 1) {
      block.rightCols<3>().noalias() = Ka[k - 1] * K[k - 1].Jr_inv_diag;
    } else {
      block.rightCols<3>().setZero();
    }
    if (k <= 2) block.rightCols<3>().noalias() -= Ka[k] * K[k].Jl_inv_diag;
  }
}

// dw_s (body angular acceleration [rad/s^2]) and, if J_dws_ctrl != nullptr, its Jacobian.
inline void EvaluateAngularAccelerationJacobian(const SegmentKnots<double>& knots,
                                                const Segment<double>& segment,
                                                Eigen::Vector3d* dw_s,
                                                ControlPoseJacobian<3>* J_dws_ctrl) {
  internal::TraceRequest request;
  request.rates = true;
  request.acceleration = true;
  internal::SegmentTrace<double> trace;
  internal::ForwardPass(knots, segment, request, &trace);
  if (dw_s != nullptr) *dw_s = trace.aw[2];
  if (J_dws_ctrl != nullptr) AngularAccelerationJacobian(knots, segment, trace, J_dws_ctrl);
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_ANGULAR_ACCELERATION_JACOBIAN_H_
