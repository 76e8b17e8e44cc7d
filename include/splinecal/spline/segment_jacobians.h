// Analytic Jacobians of the spline's pose, body angular velocity and world linear acceleration
// with respect to the four control poses of a segment (double only).
//
// Perturbation convention (lie/se3.h, the one of the whole library): RIGHT. Control pose
// P_k -> P_k Exp(d_k), d_k = [rho; phi] (translation first); a pose-valued output
// T -> T Exp(e) is differentiated in its right tangent e. Every block below is
// d out / d d_k at d = 0, the same as lie/se3_manifold.h's SE3Manifold retracts, so
// Ceres needs only its PlusJacobian (or a Minus-based lift) on top.
//
// Derivation (docs/math.md has the long form). Notation of spline/segment.h: segment poses
// P_0..P_3, Omega_j = Log(P_{j-1}^-1 P_j), A_j = Exp(b_j Omega_j), T = P_0 A_1 A_2 A_3,
// X_j = A_{j+1} ... A_3 (X_3 = I, X_0 = A_1 A_2 A_3).
//
// 1. Knot deltas. d Omega_j = Jr^-1(Omega_j) d_j - Jl^-1(Omega_j) d_{j-1}   (cached per knot,
//    KnotDeltaJacobians).
// 2. Scaled exponentials. Exp(b (Omega + dOmega)) ~ Exp(b Omega) Exp(E dOmega) with
//    E = b Jr(b Omega) (SE(3) right Jacobian of the scaled twist; internal::ScaledQRight).
// 3. Pose. P_0 Exp(d_0) A_1 A_2 A_3 = T Exp(Ad(X_0^-1) d_0), and perturbing A_j by Exp(eps) moves
//    T by Exp(Ad(X_j^-1) eps), so
//        e = Ad(X_0^-1) d_0 + sum_j F_j dOmega_j,      F_j = Ad(X_j^-1) E_j,
//        J_T_0 = Ad(X_0^-1) - F_1 Jl^-1_1,     J_T_1 = F_1 Jr^-1_1 - F_2 Jl^-1_2,
//        J_T_2 = F_2 Jr^-1_2 - F_3 Jl^-1_3,    J_T_3 = F_3 Jr^-1_3.
//    All factors are block upper-triangular [[D, U], [0, D]] and multiply as such
//    ((D1, U1)(D2, U2) = (D1 D2, D1 U2 + U1 D2)). The rotation rows depend on phi only:
//        d phi_T = S_0 d phi_0 + sum_j S_j d phi_j(Omega),
//        S_0 = R_X0^T,  S_j = R_Xj^T b_j Jr(b_j phi_j).
// 4. Body angular velocity (an SO(3) recursion, segment.h): w_1 = bdot_1 phi_1,
//    w_j = R_j^T w_{j-1} + bdot_j phi_j, and R_j(phi + d) = R_j Exp(b_j Jr(b_j phi_j) d) gives
//    d(R_j^T x) = [R_j^T x]x b_j Jr(b_j phi_j) d. Hence, with K_j = d w_s / d phi_j:
//        K_3 = [y_3]x b_3 Jr_3 + bdot_3 I,          y_j = R_j^T w_{j-1}
//        K_2 = R_3^T ([y_2]x b_2 Jr_2 + bdot_2 I),   K_1 = R_3^T R_2^T bdot_1,
//    and J_w_k = [0, K_{k} Jr^-1_k(phi) - K_{k+1} Jl^-1_{k+1}(phi)] (terms that exist).
// 5. Linear acceleration, reverse mode through the twist recursion of segment.h. The output
//    a_s = R^T d2p/dt2 = alpha.v + w x v has row gradients (3x6, [trans | rot] columns)
//        G_xi3 = [[w]x, -[v]x],   G_alpha3 = [I, 0].
//    Step j (j = 3, 2) of xi_j = y + bdot Omega, alpha_j = z + bdot ad(y) Omega + bddot Omega,
//    y = Ad(A_j^-1) xi_{j-1}, z = Ad(A_j^-1) alpha_{j-1}, and, for A_j -> A_j Exp(eps),
//    d(Ad(A_j^-1) x) = ad(Ad(A_j^-1) x) eps  (Ad(Exp(-eps)) ~ I - ad(eps)):
//        G_y       = G_xi - bdot G_alpha ad(Omega_j)
//        G_Omega_j = bdot G_xi + bddot G_alpha + bdot G_alpha ad(y)
//                    + (G_y ad(y) + G_alpha ad(z)) E_j
//        G_xi     <- G_y Ad(A_j^-1),   G_alpha <- G_alpha Ad(A_j^-1)
//    and G_Omega_1 = bdot_1 G_xi + bddot_1 G_alpha. Outputs o with do = L da_s + N dphi_T get
//    L G_Omega_j + [0, N S_j] per Omega_j and [0, N S_0] directly on d_0, then step 1's chain:
//        a_w = R a_s:                 L = R_w_s,  N = -R_w_s [a_s]x
//        f = R^T (a_w - g_w) = a_s - R^T g_w:   L = I,  N = -[R^T g_w]x   (imu/imu_model.h)
#ifndef SPLINECAL_SPLINE_SEGMENT_JACOBIANS_H_
#define SPLINECAL_SPLINE_SEGMENT_JACOBIANS_H_

#include <glog/logging.h>

#include <Eigen/Core>
#include <array>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/spline/basis.h"
#include "splinecal/spline/segment.h"

namespace splinecal {

// Jacobian of a kRows-dimensional output with respect to the four control poses of a segment
// (local support): blocks[k] = d out / d d_{first_index + k}, right perturbation
// T_{first_index+k} Exp(d), d = [rho; phi]. Control poses outside the segment have zero blocks.
template <int kRows>
struct ControlPoseJacobian {
  int first_index = 0;
  std::array<Eigen::Matrix<double, kRows, 6>, kSplineOrder> blocks;
};

namespace internal {

// A 3x6 row block [v | w] (columns: translation tangent, rotation tangent).
struct Rows3x6 {
  Eigen::Matrix3d v;
  Eigen::Matrix3d w;
};

// M Hat(x) without forming the hat: column c of M [x]x is M ([x]x e_c).
inline Eigen::Matrix3d MulHat(const Eigen::Matrix3d& M, const Eigen::Vector3d& x) {
  Eigen::Matrix3d out;
  out.col(0) = x(2) * M.col(1) - x(1) * M.col(2);
  out.col(1) = x(0) * M.col(2) - x(2) * M.col(0);
  out.col(2) = x(1) * M.col(0) - x(0) * M.col(1);
  return out;
}

// G Ad(A^-1), Ad(A^-1) = [[R^T, -R^T [t]x], [0, R^T]].
inline Rows3x6 MulAdInverse(const Rows3x6& G, const Eigen::Matrix3d& R, const Eigen::Vector3d& t) {
  Rows3x6 out;
  out.v = G.v * R.transpose();
  out.w = G.w * R.transpose() - MulHat(out.v, t);
  return out;
}

// G ad([yv; yw]), ad = [[yw]x, [yv]x], [0, [yw]x]].
inline Rows3x6 MulAd(const Rows3x6& G, const Eigen::Vector3d& yv, const Eigen::Vector3d& yw) {
  Rows3x6 out;
  out.v = MulHat(G.v, yw);
  out.w = MulHat(G.v, yv) + MulHat(G.w, yw);
  return out;
}

// G [[D, U], [0, D]].
inline Rows3x6 MulBlockTri(const Rows3x6& G, const Eigen::Matrix3d& D, const Eigen::Matrix3d& U) {
  Rows3x6 out;
  out.v = G.v * D;
  out.w = G.v * U + G.w * D;
  return out;
}

inline void AddScaled(double s, const Rows3x6& G, Rows3x6* out) {
  out->v += s * G.v;
  out->w += s * G.w;
}

inline void CheckJacobianCaches(const SegmentKnots<double>& knots) {
  CHECK(knots.jacobians != nullptr)
      << "spline Jacobians need the knot Jacobian caches (SegmentKnotData with_jacobians)";
}

// Step 1 of the derivation: blocks from the gradients w.r.t. Omega_1..3 (G[0..2]) and a direct
// rotation term on d_0 (N_S0, the [0, N S_0] block; may be zero).
inline void ChainToControlPoses(const SegmentKnots<double>& knots,
                                const std::array<Rows3x6, 3>& G,
                                const Eigen::Matrix3d& N_S0,
                                ControlPoseJacobian<3>* J) {
  const KnotDeltaJacobians* K = knots.jacobians;
  J->first_index = knots.first_index;
  // Knot j contributes G_j Jr^-1(Omega_j) to block j+1 (`next`) and -G_j Jl^-1(Omega_j) to block
  // j (`prev`), with G [[D, U], [0, D]] = [G.v D, G.v U + G.w D] and D = I +- 1/2 P + c P^2
  // (P = [phi_j]x). Each block is written once (assigned, not zeroed and accumulated).
  std::array<Eigen::Matrix<double, 3, 6>, 3> next;
  std::array<Eigen::Matrix<double, 3, 6>, 3> prev;
  for (int j = 0; j < 3; ++j) {
    const Rows3x6& g = G[j];
    const KnotDeltaJacobians& c = K[j];
    const Eigen::Vector3d& phi = knots.deltas[j].phi;
    const Eigen::Matrix3d gv_p = MulHat(g.v, phi);
    const Eigen::Matrix3d gw_p = MulHat(g.w, phi);
    const Eigen::Matrix3d gv_even = g.v + c.inv_c * MulHat(gv_p, phi);  // G.v (I + c P^2)
    const Eigen::Matrix3d gw_even = g.w + c.inv_c * MulHat(gw_p, phi);
    next[j].leftCols<3>() = gv_even + 0.5 * gv_p;
    next[j].rightCols<3>() = gw_even + 0.5 * gw_p;
    next[j].rightCols<3>().noalias() += g.v * c.Jr_inv_upper;
    prev[j].leftCols<3>() = gv_even - 0.5 * gv_p;
    prev[j].rightCols<3>() = gw_even - 0.5 * gw_p;
    prev[j].rightCols<3>().noalias() += g.v * c.Jl_inv_upper;
  }
  J->blocks[0].leftCols<3>() = -prev[0].leftCols<3>();
  J->blocks[0].rightCols<3>() = N_S0 - prev[0].rightCols<3>();
  J->blocks[1] = next[0] - prev[1];
  J->blocks[2] = next[1] - prev[2];
  J->blocks[3] = next[2];
}

// Rotation sensitivities S_0..S_3 of the output orientation (derivation, step 3).
inline void RotationSensitivities(const SegmentKnots<double>& knots,
                                  const SegmentTrace<double>& trace,
                                  std::array<Eigen::Matrix3d, 4>* S) {
  const Eigen::Matrix3d R3t = trace.A[2].R.transpose();
  const Eigen::Matrix3d R23t = R3t * trace.A[1].R.transpose();  // R_X1^T
  Eigen::Matrix3d b_Jr;
  ScaledRightJacobianSO3(knots.deltas[2], trace.A[2], &b_Jr);
  (*S)[3] = b_Jr;
  ScaledRightJacobianSO3(knots.deltas[1], trace.A[1], &b_Jr);
  (*S)[2] = R3t * b_Jr;
  ScaledRightJacobianSO3(knots.deltas[0], trace.A[0], &b_Jr);
  (*S)[1] = R23t * b_Jr;
  (*S)[0] = R23t * trace.A[0].R.transpose();
}

// a^ b^ = b a^T - (a . b) I.
inline Eigen::Matrix3d HatHat(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  Eigen::Matrix3d m = b * a.transpose();
  m.diagonal().array() -= a.dot(b);
  return m;
}

// Hat(a) M: column c is a x M.col(c).
inline Eigen::Matrix3d HatMul(const Eigen::Vector3d& a, const Eigen::Matrix3d& M) {
  Eigen::Matrix3d out;
  out.col(0) = a.cross(M.col(0));
  out.col(1) = a.cross(M.col(1));
  out.col(2) = a.cross(M.col(2));
  return out;
}

// m += s Hat(x).
inline void AddHat(double s, const Eigen::Vector3d& x, Eigen::Matrix3d* m) {
  const Eigen::Vector3d sx = s * x;
  (*m)(0, 1) -= sx(2);
  (*m)(0, 2) += sx(1);
  (*m)(1, 0) += sx(2);
  (*m)(1, 2) -= sx(0);
  (*m)(2, 0) -= sx(1);
  (*m)(2, 1) += sx(0);
}

inline TraceRequest FullTraceRequest() {
  TraceRequest request;
  request.translation = true;
  request.rates = true;
  request.linear = true;
  request.acceleration = true;
  request.q_coefficients = true;
  return request;
}

// Gradients (3x6 each) of f = a_s - R_w_s^T g_w (or of a_s alone when g_s == nullptr) with
// respect to Omega_1..3 (G[0..2]), and the direct rotation block on d_0 (*J0_rot, the
// [0, N S_0] of step 5; zero without gravity). g_s = R_w_s^T g_w. The trace must hold the full
// forward pass (FullTraceRequest).
//
// This is step 5 of the header comment with its structure exploited (L = I):
//  * step 3 starts from G_alpha = [I, 0] and G_xi = [[w]x, -[v]x], so G_y = [[a]x, [c]x] with
//    a = w_3 - bdot_3 phi_3 = y_3.w and c = -(v_3 + bdot_3 rho_3), and every product with an
//    ad() is a product of two hats: [a]x [b]x = b a^T - (a.b) I.
//  * after step 3, G_xi = R_3^T [[p]x, [q]x - [p]x [t_3]x] (p = R_3 a, q = R_3 c) and
//    G_alpha = R_3^T [I, -[t_3]x], since [a]x R^T = R^T [R a]x. Step 2 runs on the bracketed
//    (primed) gradients, which keep that cheap structure, and R_3^T is applied once at the end.
//    The gravity terms N S_j with N = -[g_s]x move into the primed frame as -[R_3 g_s]x.
inline void SpecificForceGradients(const SegmentKnots<double>& knots,
                                   const Segment<double>& segment,
                                   const SegmentTrace<double>& trace,
                                   const Eigen::Vector3d* g_s,
                                   std::array<Rows3x6, 3>* G,
                                   Eigen::Matrix3d* J0_rot) {
  const ScaledExp<double>& A1 = trace.A[0];
  const ScaledExp<double>& A2 = trace.A[1];
  const ScaledExp<double>& A3 = trace.A[2];
  const KnotDelta<double>& D2 = knots.deltas[1];
  const KnotDelta<double>& D3 = knots.deltas[2];
  Eigen::Matrix3d b_Jr;
  Eigen::Matrix3d b_Qr;

  // Step 3 (Omega_3).
  const double bd3 = segment.b_dot[3];
  const double bdd3 = segment.b_ddot[3];
  const Eigen::Vector3d& v3 = trace.v[2];
  const Eigen::Vector3d& yv3 = trace.yv[2];
  const Eigen::Vector3d& yw3 = trace.yw[2];
  const Eigen::Vector3d a = yw3;
  const Eigen::Vector3d c = -(v3 + bd3 * D3.rho);
  Eigen::Matrix3d Hv = HatHat(a, yw3);  // H = G_y ad(y) + G_alpha ad(z)
  AddHat(1.0, trace.zw[2], &Hv);
  Eigen::Matrix3d Hw = HatHat(a, yv3) + HatHat(c, yw3);
  AddHat(1.0, trace.zv[2], &Hw);
  ScaledRightJacobianSO3(D3, A3, &b_Jr);
  b_Qr = A3.b * ScaledQRight(D3, knots.jacobians[2], A3);
  Rows3x6& G3 = (*G)[2];
  G3.v.noalias() = Hv * b_Jr;  // + bdot G_xi + bddot G_alpha + bdot G_alpha ad(y)
  AddHat(bd3, trace.w[2] + yw3, &G3.v);
  G3.v.diagonal().array() += bdd3;
  G3.w.noalias() = Hv * b_Qr;
  G3.w.noalias() += Hw * b_Jr;
  AddHat(bd3, yv3 - v3, &G3.w);
  if (g_s != nullptr) G3.w -= HatMul(*g_s, b_Jr);  // N S_3

  // Step 2 (Omega_2), primed: G = R_3^T G'.
  const Eigen::Vector3d p = A3.R * a;
  const Eigen::Vector3d q = A3.R * c;
  const Eigen::Vector3d& t = A3.t;
  const double bd2 = segment.b_dot[2];
  const double bdd2 = segment.b_ddot[2];
  const Eigen::Vector3d& yv2 = trace.yv[1];
  const Eigen::Vector3d& yw2 = trace.yw[1];
  const Eigen::Vector3d e = p - bd2 * D2.phi;  // G'_y = [[e]x, M]
  const Eigen::Matrix3d pt = HatHat(p, t);
  Eigen::Matrix3d M = bd2 * HatHat(t, D2.phi) - pt;
  AddHat(1.0, q - bd2 * D2.rho, &M);
  Eigen::Matrix3d Hv2 = HatHat(e, yw2);
  AddHat(1.0, trace.zw[1], &Hv2);
  Eigen::Matrix3d Hw2 = HatHat(e, yv2) + MulHat(M, yw2) - HatHat(t, trace.zw[1]);
  AddHat(1.0, trace.zv[1], &Hw2);
  ScaledRightJacobianSO3(D2, A2, &b_Jr);
  b_Qr = A2.b * ScaledQRight(D2, knots.jacobians[1], A2);
  Rows3x6 G2p;
  G2p.v.noalias() = Hv2 * b_Jr;
  AddHat(bd2, p + yw2, &G2p.v);
  G2p.v.diagonal().array() += bdd2;
  G2p.w.noalias() = Hv2 * b_Qr;
  G2p.w.noalias() += Hw2 * b_Jr;
  G2p.w -= bd2 * (pt + HatHat(t, yw2));
  AddHat(bd2, q + yv2, &G2p.w);
  AddHat(-bdd2, t, &G2p.w);
  Eigen::Vector3d g_p = Eigen::Vector3d::Zero();
  if (g_s != nullptr) {
    g_p = A3.R * (*g_s);
    G2p.w -= HatMul(g_p, b_Jr);  // N S_2 (primed)
  }

  // Step 1 (Omega_1): G'_Omega1 = bdot_1 G'_y Ad(A_2^-1) + bddot_1 G'_alpha Ad(A_2^-1).
  const Eigen::Matrix3d R2t = A2.R.transpose();
  const double bd1 = segment.b_dot[1];
  const double bdd1 = segment.b_ddot[1];
  Rows3x6 G1p;
  G1p.v = bd1 * HatMul(e, R2t) + bdd1 * R2t;
  G1p.w.noalias() = bd1 * (M * R2t);
  G1p.w -= MulHat(G1p.v, A2.t) + bdd1 * HatMul(t, R2t);
  const Eigen::Matrix3d R3t = A3.R.transpose();
  if (g_s != nullptr) {
    ScaledRightJacobianSO3(knots.deltas[0], A1, &b_Jr);
    const Eigen::Matrix3d R21t = R2t * A1.R.transpose();
    G1p.w -= HatMul(g_p, R2t * b_Jr);              // N S_1 (primed)
    J0_rot->noalias() = -R3t * HatMul(g_p, R21t);  // N S_0
  } else {
    J0_rot->setZero();
  }
  (*G)[1].v.noalias() = R3t * G2p.v;
  (*G)[1].w.noalias() = R3t * G2p.w;
  (*G)[0].v.noalias() = R3t * G1p.v;
  (*G)[0].w.noalias() = R3t * G1p.w;
}

// Jacobian of the specific force f = R_w_s^T (a_w - g_w) (without bias) w.r.t. the control
// poses; the trace holds the full forward pass.
inline void SpecificForceJacobian(const SegmentKnots<double>& knots,
                                  const Segment<double>& segment,
                                  const SegmentTrace<double>& trace,
                                  const Eigen::Vector3d& g_s,
                                  ControlPoseJacobian<3>* J) {
  std::array<Rows3x6, 3> G;
  Eigen::Matrix3d J0_rot;
  SpecificForceGradients(knots, segment, trace, &g_s, &G, &J0_rot);
  ChainToControlPoses(knots, G, J0_rot, J);
}

// Jacobian of a_w = R_w_s a_s: L = R_w_s, N = -R_w_s [a_s]x (step 5).
inline void WorldAccelerationJacobian(const SegmentKnots<double>& knots,
                                      const Segment<double>& segment,
                                      const SegmentTrace<double>& trace,
                                      const Eigen::Matrix3d& R_w_s,
                                      const Eigen::Vector3d& a_s,
                                      ControlPoseJacobian<3>* J) {
  std::array<Rows3x6, 3> G;
  Eigen::Matrix3d unused;
  SpecificForceGradients(knots, segment, trace, nullptr, &G, &unused);
  std::array<Eigen::Matrix3d, 4> S;
  RotationSensitivities(knots, trace, &S);
  const Eigen::Matrix3d N = -MulHat(R_w_s, a_s);
  for (int j = 0; j < 3; ++j) {
    G[j].v = R_w_s * G[j].v;
    G[j].w = R_w_s * G[j].w + N * S[j + 1];
  }
  ChainToControlPoses(knots, G, N * S[0], J);
}

}  // namespace internal

// T_w_s and d(T_w_s)/d(control poses), 6x6 blocks in the right tangent of T_w_s
// (T_w_s(P_k Exp(d)) ~ T_w_s Exp(J.blocks[k] d)). Outputs optional (nullptr = skip).
// Needs knots with Jacobian caches (SE3Spline<double> always has them).
inline void EvaluatePoseJacobian(const SegmentKnots<double>& knots,
                                 const Segment<double>& segment,
                                 SE3d* T_w_s,
                                 ControlPoseJacobian<6>* J_pose_ctrl) {
  internal::TraceRequest request;
  request.translation = true;
  request.q_coefficients = J_pose_ctrl != nullptr;
  internal::SegmentTrace<double> trace;
  internal::ForwardPass(knots, segment, request, &trace);
  if (T_w_s != nullptr) *T_w_s = internal::SegmentPose(knots, trace);
  if (J_pose_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  const KnotDeltaJacobians* K = knots.jacobians;
  // Suffix products X_j = A_{j+1} .. A_3: rotation transposes and translations.
  std::array<Eigen::Matrix3d, 4> RXt;  // R_Xj^T
  std::array<Eigen::Vector3d, 4> tX;   // t_Xj
  RXt[3].setIdentity();
  tX[3].setZero();
  for (int j = 2; j >= 0; --j) {  // X_j = A_{j+1} X_{j+1}
    const internal::ScaledExp<double>& A = trace.A[j];
    RXt[j] = RXt[j + 1] * A.R.transpose();
    tX[j] = A.t + A.R * tX[j + 1];
  }
  // F_j = Ad(X_j^-1) E_j = (R_Xj^T b Jr, R_Xj^T (b Qr - [t_Xj]x b Jr)), j = 1..3.
  std::array<Eigen::Matrix3d, 3> FD;
  std::array<Eigen::Matrix3d, 3> FU;
  for (int j = 0; j < 3; ++j) {
    const internal::ScaledExp<double>& A = trace.A[j];
    Eigen::Matrix3d b_Jr;
    internal::ScaledRightJacobianSO3(knots.deltas[j], A, &b_Jr);
    const Eigen::Matrix3d b_Qr = A.b * internal::ScaledQRight(knots.deltas[j], K[j], A);
    FD[j] = RXt[j + 1] * b_Jr;
    FU[j] = RXt[j + 1] * (b_Qr - Hat(tX[j + 1]) * b_Jr);
  }
  J_pose_ctrl->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    Eigen::Matrix3d D;
    Eigen::Matrix3d U;
    if (k == 0) {  // Ad(X_0^-1) = (R_X0^T, -R_X0^T [t_X0]x)
      D = RXt[0];
      U = -internal::MulHat(RXt[0], tX[0]);
    } else {  // + F_k Jr^-1(Omega_k)
      D = FD[k - 1] * K[k - 1].Jr_inv_diag;
      U = FD[k - 1] * K[k - 1].Jr_inv_upper + FU[k - 1] * K[k - 1].Jr_inv_diag;
    }
    if (k <= 2) {  // - F_{k+1} Jl^-1(Omega_{k+1})
      D -= FD[k] * K[k].Jl_inv_diag;
      U -= FD[k] * K[k].Jl_inv_upper + FU[k] * K[k].Jl_inv_diag;
    }
    Eigen::Matrix<double, 6, 6>& block = J_pose_ctrl->blocks[k];
    block.topLeftCorner<3, 3>() = D;
    block.topRightCorner<3, 3>() = U;
    block.bottomLeftCorner<3, 3>().setZero();
    block.bottomRightCorner<3, 3>() = D;
  }
}

// w_s (body angular velocity) and d w_s / d(control poses), 3x6 blocks whose translation
// columns are zero (the orientation of the spline depends on control rotations only).
inline void EvaluateAngularVelocityJacobian(const SegmentKnots<double>& knots,
                                            const Segment<double>& segment,
                                            Eigen::Vector3d* w_s,
                                            ControlPoseJacobian<3>* J_ws_ctrl) {
  internal::TraceRequest request;
  request.rates = true;
  internal::SegmentTrace<double> trace;
  internal::ForwardPass(knots, segment, request, &trace);
  if (w_s != nullptr) *w_s = trace.w[2];
  if (J_ws_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  const KnotDeltaJacobians* K = knots.jacobians;
  // K_j = d w_s / d phi_j (derivation, step 4).
  std::array<Eigen::Matrix3d, 3> Kw;
  const Eigen::Matrix3d R3t = trace.A[2].R.transpose();
  Eigen::Matrix3d b_Jr;
  internal::ScaledRightJacobianSO3(knots.deltas[2], trace.A[2], &b_Jr);
  Kw[2] = Hat(trace.yw[2]) * b_Jr;
  Kw[2].diagonal().array() += segment.b_dot[3];
  internal::ScaledRightJacobianSO3(knots.deltas[1], trace.A[1], &b_Jr);
  Eigen::Matrix3d inner = Hat(trace.yw[1]) * b_Jr;
  inner.diagonal().array() += segment.b_dot[2];
  Kw[1] = R3t * inner;
  Kw[0] = (segment.b_dot[1] * R3t) * trace.A[1].R.transpose();
  J_ws_ctrl->first_index = knots.first_index;
  for (int k = 0; k < kSplineOrder; ++k) {
    Eigen::Matrix3d Jw;
    if (k >= 1) {
      Jw = Kw[k - 1] * K[k - 1].Jr_inv_diag;
    } else {
      Jw.setZero();
    }
    if (k <= 2) Jw -= Kw[k] * K[k].Jl_inv_diag;
    J_ws_ctrl->blocks[k].leftCols<3>().setZero();
    J_ws_ctrl->blocks[k].rightCols<3>() = Jw;
  }
}

// a_w (world linear acceleration d2p_w_s/dt2) and d a_w / d(control poses), 3x6 blocks.
inline void EvaluateLinearAccelerationJacobian(const SegmentKnots<double>& knots,
                                               const Segment<double>& segment,
                                               Eigen::Vector3d* a_w,
                                               ControlPoseJacobian<3>* J_aw_ctrl) {
  internal::TraceRequest request = internal::FullTraceRequest();
  request.q_coefficients = J_aw_ctrl != nullptr;
  internal::SegmentTrace<double> trace;
  internal::ForwardPass(knots, segment, request, &trace);
  const Eigen::Matrix3d R_w_s = internal::SegmentRotation(knots, trace);
  const Eigen::Vector3d a_s = trace.av[2] + trace.w[2].cross(trace.v[2]);
  if (a_w != nullptr) *a_w = R_w_s * a_s;
  if (J_aw_ctrl == nullptr) return;
  internal::CheckJacobianCaches(knots);
  internal::WorldAccelerationJacobian(knots, segment, trace, R_w_s, a_s, J_aw_ctrl);
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_SEGMENT_JACOBIANS_H_
