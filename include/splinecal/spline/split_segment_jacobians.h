// Analytic Jacobians of the split SO(3) x R^3 spline (spline/split_segment.h) with respect to the
// four control poses of a segment (double only): pose, world linear acceleration and the
// specific force the accelerometer measures. The body angular velocity's Jacobian is the coupled
// spline's (EvaluateAngularVelocityJacobian, spline/segment_jacobians.h): the two models share
// their rotation.
//
// Tangent. The control poses stay splinecal's SE(3) poses with the RIGHT perturbation of the
// whole library (lie/se3.h, SE3Manifold): P_k -> P_k Exp(d_k), d_k = [rho_k; phi_k]. To first
// order that moves p_k by R_k rho_k and R_k to R_k Exp(phi_k) (the translation of T Exp(d) is
// p + R Jl(phi) rho), so for any output o
//
//     d o / d rho_k = (d o / d p_k) R_k,        d o / d phi_k = the SO(3) spline's Jacobian,
//
// and the split model keeps one shape of parameter block, manifold and covariance with the
// coupled one (docs/conventions.md, "The spline").
//
// Derivation (docs/math.md, section 6, has the long form). Notation of spline/segment.h and
// spline/segment_jacobians.h: A_j = Exp(b_j phi_j), X_j = A_{j+1} .. A_3 (X_3 = I), so that
// R_w_s = R_0 X_0, and the knot rotations move as dphi_j = Jr^-1(phi_j) phi_j - Jl^-1(phi_j)
// phi_{j-1} (KnotDeltaJacobians; here phi_k is control pose k's rotation tangent).
//
// 1. Orientation. R_w_s -> R_w_s Exp(e) with e = R_X0^T phi_0 + sum_j R_Xj^T b_j Jr(b_j phi_j)
//    dphi_j (segment_jacobians.h, step 3), so block k of d e / d phi is
//        Q_k = R_Xk^T U_k - R_X(k+1)^T V_(k+1)      (terms that exist; Q_0's first term R_X0^T),
//        U_j = b_j Jr(b_j phi_j) Jr^-1(phi_j),  V_j = b_j Jr(b_j phi_j) Jl^-1(phi_j).
//    U_j and V_j are products of polynomials in P = [phi_j]x, which commute and close under
//    P^3 = -|phi|^2 P, P^4 = -|phi|^2 P^2: with b Jr(b phi) = b I + y P + z P^2 (y = -b^2 c2,
//    z = b^3 c3; spline/segment.h) and Jr^-1, Jl^-1 = I +- 1/2 P + c P^2 (lie/so3.h),
//        (b I + y P + z P^2)(I + e P + c P^2)
//            = b I + (b e + y - |phi|^2 (y c + z e)) P + (b c + y e + z - |phi|^2 z c) P^2
//    for e = +1/2 (U) and e = -1/2 (V): three scalars each, no 3x3 product. Grouped by the
//    common factors R_X2^T = A_3^T and R_X1^T = A_3^T A_2^T:
//        Q_3 = U_3,   Q_2 = A_3^T U_2 - V_3,   Q_1 = A_3^T (A_2^T U_1 - V_2),
//        Q_0 = A_3^T A_2^T (A_1^T - V_1)                        (five 3x3 products)
// 2. Position. p = sum_k B_k p_k (B_k = Bt_k - Bt_{k+1}, spline/basis.h), and the pose's right
//    tangent moves by e_rho = R_w_s^T dp, so d e_rho / d rho_k = B_k R_w_s^T R_k, with
//    R_w_s^T = R_X0^T R_0^T. The position does not depend on phi_k, nor the orientation on
//    rho_k: the 6x6 pose block is block-diagonal, [[B_k R_w_s^T R_k, 0], [0, Q_k]].
// 3. World acceleration a_w = sum_k Bddot_k p_k: block k = [Bddot_k R_k, 0].
// 4. Specific force f = R_w_s^T (a_w - g_w) (imu/imu_model.h adds b_a). Under R_w_s -> R_w_s
//    Exp(e), f -> Exp(-e) f = f + [f]x e, so
//        d f / d rho_k = Bddot_k R_w_s^T R_k,      d f / d phi_k = [f]x Q_k,
//    and d f / d g_w = -R_w_s^T. No backward pass through the rates: the coupled spline's
//    acceleration depends on every control rotation through rho, which is what makes its
//    Jacobian expensive (spline/segment_jacobians.h, step 5).
#ifndef SPLINECAL_SPLINE_SPLIT_SEGMENT_JACOBIANS_H_
#define SPLINECAL_SPLINE_SPLIT_SEGMENT_JACOBIANS_H_

#include <Eigen/Core>
#include <array>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/basis.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/split_segment.h"

namespace splinecal {
namespace internal {

// U = b Jr(b phi) Jr^-1(phi) and V = b Jr(b phi) Jl^-1(phi) for one knot at A = Exp(b phi)
// (step 1: polynomials in [phi]x with three scalar coefficients each).
inline void ScaledJacobianTimesInverses(const KnotDelta<double>& delta,
                                        const KnotDeltaJacobians& J,
                                        const ScaledExp<double>& A,
                                        Eigen::Matrix3d* U,
                                        Eigen::Matrix3d* V) {
  const double b = A.b;
  const double y = -(b * b * A.k.c2);
  const double z = b * b * b * A.k.c3;
  const double c = J.inv_c;
  const double t = delta.theta_sq;
  const double even_p = y - t * y * c;           // P coefficient without the +-1/2 terms
  const double half_p = 0.5 * (b - t * z);       // ... and the +-1/2 terms
  const double even_pp = b * c + z - t * z * c;  // P^2 coefficient without the +-1/2 terms
  const double half_pp = 0.5 * y;
  SetIdentityHatSquare(b, even_p + half_p, even_pp + half_pp, delta.phi, t, U);
  SetIdentityHatSquare(b, even_p - half_p, even_pp - half_pp, delta.phi, t, V);
}

// Step 1: Q_k = d e / d phi_k, the orientation's Jacobian (3x3 blocks), and
// R_X0^T = R_w_s^T R_0. `trace` holds the rotation forward pass (SplitForwardPass).
inline void SplitRotationJacobian(const SegmentKnots<double>& knots,
                                  const SegmentTrace<double>& trace,
                                  std::array<Eigen::Matrix3d, 4>* Q,
                                  Eigen::Matrix3d* R_X0_t) {
  std::array<Eigen::Matrix3d, 3> U;
  std::array<Eigen::Matrix3d, 3> V;
  for (int j = 0; j < 3; ++j) {
    ScaledJacobianTimesInverses(knots.deltas[j], knots.jacobians[j], trace.A[j], &U[j], &V[j]);
  }
  const auto A3t = trace.A[2].R.transpose();
  const auto A2t = trace.A[1].R.transpose();
  const auto A1t = trace.A[0].R.transpose();
  Eigen::Matrix3d Y = -V[1];  // A_2^T U_1 - V_2
  Y.noalias() += A2t * U[0];
  Eigen::Matrix3d R_X1_t;
  R_X1_t.noalias() = A3t * A2t;
  (*Q)[3] = U[2];
  (*Q)[2] = -V[2];
  (*Q)[2].noalias() += A3t * U[1];
  (*Q)[1].noalias() = A3t * Y;
  V[0] = A1t - V[0];
  (*Q)[0].noalias() = R_X1_t * V[0];
  R_X0_t->noalias() = R_X1_t * A1t;
}

// R_w_s^T R_k, k = 0..3 (step 2), and R_w_s^T itself, from R_X0^T = R_w_s^T R_0. Needs the
// rotation matrices of P_1..P_3 (knots with Jacobian caches).
inline void BodyFromControlRotations(const SegmentKnots<double>& knots,
                                     const Eigen::Matrix3d& R_X0_t,
                                     std::array<Eigen::Matrix3d, 4>* Rt_Rk,
                                     Eigen::Matrix3d* R_s_w) {
  R_s_w->noalias() = R_X0_t * knots.R_first[0].transpose();
  (*Rt_Rk)[0] = R_X0_t;
  for (int k = 1; k < kSplineOrder; ++k) (*Rt_Rk)[k].noalias() = (*R_s_w) * knots.R_first[k];
}

// Step 4: f = R_w_s^T (a_w - g_w) and its control-pose Jacobian (J may be null: then only f,
// and R_s_w = R_w_s^T when that is not null). `trace` holds the rotation forward pass
// (SplitForwardPass).
inline void SplitSpecificForce(const SegmentKnots<double>& knots,
                               const Segment<double>& segment,
                               const SegmentTrace<double>& trace,
                               const Eigen::Vector3d& g_w,
                               Eigen::Vector3d* f,
                               ControlPoseJacobian<3>* J,
                               Eigen::Matrix3d* R_s_w) {
  const Eigen::Vector3d a_minus_g = BlendPositionSteps(knots, segment.b_ddot) - g_w;
  if (J == nullptr) {
    if (R_s_w == nullptr) {
      *f = RotateToBody(knots, trace, a_minus_g);
      return;
    }
    *R_s_w = SegmentRotation(knots, trace).transpose();
    f->noalias() = (*R_s_w) * a_minus_g;
    return;
  }
  CheckJacobianCaches(knots);
  std::array<Eigen::Matrix3d, 4> Q;
  Eigen::Matrix3d R_X0_t;
  SplitRotationJacobian(knots, trace, &Q, &R_X0_t);
  std::array<Eigen::Matrix3d, 4> Rt_Rk;
  Eigen::Matrix3d Rt;
  BodyFromControlRotations(knots, R_X0_t, &Rt_Rk, &Rt);
  f->noalias() = Rt * a_minus_g;
  if (R_s_w != nullptr) *R_s_w = Rt;
  const Eigen::Vector4d weights = BasisFromCumulative<double>(segment.b_ddot);  // Bddot_k
  J->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    J->blocks[k].leftCols<3>() = weights[k] * Rt_Rk[k];
    J->blocks[k].rightCols<3>() = HatMul(*f, Q[k]);
  }
}

}  // namespace internal

// T_w_s and d(T_w_s)/d(control poses) of the split spline, 6x6 blocks in the right tangent of
// T_w_s (T_w_s(P_k Exp(d)) ~ T_w_s Exp(J.blocks[k] d)), block-diagonal (steps 1-2). Outputs
// optional (nullptr = skip). Needs knots with Jacobian caches.
inline void EvaluateSplitPoseJacobian(const SegmentKnots<double>& knots,
                                      const Segment<double>& segment,
                                      SE3d* T_w_s,
                                      ControlPoseJacobian<6>* J_pose_ctrl) {
  internal::SegmentTrace<double> trace;
  internal::SplitForwardPass(knots, segment, false, false, &trace);
  if (T_w_s != nullptr) *T_w_s = internal::SplitSegmentPose(knots, segment, trace);
  if (J_pose_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  std::array<Eigen::Matrix3d, 4> rotation;
  Eigen::Matrix3d R_X0_t;
  internal::SplitRotationJacobian(knots, trace, &rotation, &R_X0_t);
  std::array<Eigen::Matrix3d, 4> Rt_Rk;
  Eigen::Matrix3d Rt;
  internal::BodyFromControlRotations(knots, R_X0_t, &Rt_Rk, &Rt);
  const Eigen::Vector4d weights = BasisFromCumulative<double>(segment.b);  // B_k
  J_pose_ctrl->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    Eigen::Matrix<double, 6, 6>& block = J_pose_ctrl->blocks[k];
    block.topLeftCorner<3, 3>() = weights[k] * Rt_Rk[k];
    block.topRightCorner<3, 3>().setZero();
    block.bottomLeftCorner<3, 3>().setZero();
    block.bottomRightCorner<3, 3>() = rotation[k];
  }
}

// a_w (world linear acceleration d2p_w_s/dt2) and d a_w / d(control poses) of the split spline,
// 3x6 blocks [Bddot_k R_k, 0] (step 3). J_aw_ctrl may be nullptr; it needs knots with Jacobian
// caches (for R_1..R_3).
inline void EvaluateSplitLinearAccelerationJacobian(const SegmentKnots<double>& knots,
                                                    const Segment<double>& segment,
                                                    Eigen::Vector3d* a_w,
                                                    ControlPoseJacobian<3>* J_aw_ctrl) {
  if (a_w != nullptr) *a_w = internal::BlendPositionSteps(knots, segment.b_ddot);
  if (J_aw_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  const Eigen::Vector4d weights = BasisFromCumulative<double>(segment.b_ddot);
  J_aw_ctrl->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    J_aw_ctrl->blocks[k].leftCols<3>() = weights[k] * knots.R_first[k];
    J_aw_ctrl->blocks[k].rightCols<3>().setZero();
  }
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_SPLIT_SEGMENT_JACOBIANS_H_
