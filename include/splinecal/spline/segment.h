// One segment of the uniform cumulative cubic B-spline on SE(3): where a time falls, what the
// segment's four control poses contribute (cached per knot), and a one-pass evaluation of the
// pose and its time derivatives. SE3Spline (spline/se3_spline.h) is built on this header; cost
// functions that see only four pose blocks use SegmentKnotData directly.
//
// The spline ([CONVENTIONS "The spline"], [seed000 §3 eqs. (3), (6)], [Lovegrove13 eq. (4)]):
// for t in [t_i, t_{i+1}), u = (t - t_i) / dt, with the four control poses
// P_0..P_3 = T_{i-1}..T_{i+2} of the segment,
//
//     T_w_s(t) = P_0 A_1 A_2 A_3,     A_j = Exp(b_j Omega_j),     b_j = Bt_j(u),
//     Omega_j = Log(P_{j-1}^-1 P_j) = [rho_j; phi_j]   (Omega_{i}, Omega_{i+1}, Omega_{i+2}).
//
// Time derivatives: body twist recursion ([Sommer20] Theorem 1 / eqs. (28)-(30), the SE(3)
// form of the product rule of [seed000 eqs. (4)-(8)]). With xi = vee(T^-1 dT/dt) = [v_s; w_s]
// the body twist (v_s = R_w_s^T dp_w_s/dt, w_s the body angular velocity) of the partial
// product T_j = P_0 A_1 ... A_j:
//
//     xi_0 = 0,                       xi_j    = Ad(A_j^-1) xi_{j-1} + bdot_j Omega_j
//     alpha_0 = 0 (= dxi_0/dt),       alpha_j = Ad(A_j^-1) alpha_{j-1}
//                                               + bdot_j ad(y_j) Omega_j + bddot_j Omega_j,
//                                     y_j = Ad(A_j^-1) xi_{j-1}
//
// since T_j^-1 dT_j/dt = A_j^-1 (T_{j-1}^-1 dT_{j-1}/dt) A_j + A_j^-1 dA_j/dt with
// A_j^-1 dA_j/dt = bdot_j Hat(Omega_j), and d/dt Ad(A_j^-1) = -bdot_j ad(Omega_j) Ad(A_j^-1).
// Here Ad(A^-1) [v; w] = [R^T (v - t x w); R^T w] and ad([v; w]) [rho; phi] =
// [w x rho + v x phi; w x phi]. xi_1 = bdot_1 Omega_1 and alpha_1 = bddot_1 Omega_1: A_1 does
// not enter the body rates. From xi = xi_3, alpha = alpha_3:
//
//     w_s     = xi.w                       body angular velocity   vee(R^T dR/dt)
//     w_dot_s = alpha.w                    body angular acceleration (= R^T d(R w_s)/dt too)
//     v_w     = R_w_s xi.v                 world linear velocity   dp_w_s/dt
//     a_w     = R_w_s (alpha.v + w_s x xi.v)   world linear acceleration   d2p_w_s/dt2
//
// (p = R v  =>  p'' = R' v + R v' = R (w x v + v').) The rotation of T_w_s depends on the
// rotations of the control poses only: phi_j = Log(R_{j-1}^T R_j) and Exp([rho; phi]) has
// rotation Exp(phi), so the orientation and w_s are those of the SO(3) cumulative spline.
//
// Scaled exponentials. Every A_j = Exp(b Omega) with Omega fixed per knot: with
// x = |b phi| and the per-knot invariants theta^2 = |phi|^2, phi x rho, phi x (phi x rho)
// (KnotDelta):
//     R(A) = I + b c1 Hat(phi) + b^2 c2 Hat(phi)^2,      q(A) = [cos(x/2), b h phi]
//     t(A) = Jl(b phi) b rho = b rho + b^2 c2 (phi x rho) + b^3 c3 phi x (phi x rho)
// with h = sin(x/2)/x, c1 = sin x / x = 2 h cos(x/2), c2 = (1 - cos x)/x^2 = 2 h^2,
// c3 = (x - sin x)/x^3 = (1 - c1)/x^2 ([Barfoot17] SE(3) exponential). One sin and one cos of
// x/2 per exponential.
//
// Scalar type: templates on T (double or ceres::Jet<double, N>); the time offset u may be a Jet.
//
// References (docs/references.md)
//   [seed000]     "VIO from scratch" homework 2, §3: the Spline Fusion spline and eqs. (1)-(10).
//   [Lovegrove13] S. Lovegrove, A. Patron-Perez, G. Sibley, "Spline Fusion", BMVC 2013.
//   [Sommer20]    C. Sommer, V. Usenko, D. Schubert, N. Demmel, D. Cremers, "Efficient
//                 Derivative Computation for Cumulative B-Splines on Lie Groups", CVPR 2020.
//   [Barfoot17]   T. D. Barfoot, "State Estimation for Robotics", 2017.
#ifndef SPLINECAL_SPLINE_SEGMENT_H_
#define SPLINECAL_SPLINE_SEGMENT_H_

#include <ceres/jet.h>
#include <glog/logging.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <array>
#include <cmath>
#include <type_traits>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"
#include "splinecal/spline/basis.h"

namespace splinecal {

namespace internal {
// Puts T in a non-deduced context, so that output pointers accept a plain nullptr
// (std::type_identity_t before C++20).
template <typename T>
struct NonDeduced {
  using type = T;
};
template <typename T>
using NonDeducedT = typename NonDeduced<T>::type;
}  // namespace internal

// Where a time falls in the spline: the segment index i (t in [t_i, t_{i+1}], control poses
// i-1 .. i+2), u = (t - t_i) / dt in [0, 1], and the cumulative blending coefficients with
// their TIME derivatives. Entry 0 of each vector belongs to Bt_0 = 1; entries 1..3 blend
// Omega_i, Omega_{i+1}, Omega_{i+2}. Made by SE3Spline::SegmentAt / SegmentAtNs or MakeSegment.
template <typename T>
struct Segment {
  int index = 1;                             // i
  T u = T(0.0);                              // (t - t_i) / dt
  Eigen::Matrix<T, kSplineOrder, 1> b;       // Bt(u)
  Eigen::Matrix<T, kSplineOrder, 1> b_dot;   // dBt/dt    [1/s]
  Eigen::Matrix<T, kSplineOrder, 1> b_ddot;  // d2Bt/dt2  [1/s^2]

  // Index of the first control pose of the segment, P_0 = T_{i-1}.
  int first_index() const { return index - 1; }
};

// The segment record for index i and u (no range checks: SE3Spline::SegmentAt checks).
template <typename T>
Segment<T> MakeSegment(int index, const T& u, double dt_s) {
  const double inv_dt = 1.0 / dt_s;
  Segment<T> segment;
  segment.index = index;
  segment.u = u;
  segment.b = CumulativeBasis<0>(u);
  segment.b_dot = CumulativeBasis<1>(u) * T(inv_dt);
  segment.b_ddot = CumulativeBasis<2>(u) * T(inv_dt * inv_dt);
  return segment;
}

// Omega_k = Log(T_{k-1}^-1 T_k) = [rho; phi] and the invariants of its scaled exponentials.
// Computed once per knot when control poses change. The same record serves the split SO(3) x R^3
// model (spline/split_segment.h): its rotation steps are the same phi (the rotation of
// Log(T_{k-1}^-1 T_k) is Log(R_{k-1}^T R_k)), its position steps are dp.
template <typename T>
struct KnotDelta {
  Vector3<T> rho;
  Vector3<T> phi;
  T theta_sq;                  // |phi|^2
  Vector3<T> phi_x_rho;        // phi x rho
  Vector3<T> phi_x_phi_x_rho;  // phi x (phi x rho)
  Vector3<T> dp;               // p_k - p_{k-1}, world frame [m] (split model only)
};

template <typename T>
KnotDelta<T> MakeKnotDelta(const SE3<T>& T_prev, const SE3<T>& T_next) {
  const Vector6<T> omega = (T_prev.inverse() * T_next).Log();
  KnotDelta<T> delta;
  delta.rho = omega.template head<3>();
  delta.phi = omega.template tail<3>();
  delta.theta_sq = delta.phi.squaredNorm();
  delta.phi_x_rho = delta.phi.cross(delta.rho);
  delta.phi_x_phi_x_rho = delta.phi.cross(delta.phi_x_rho);
  delta.dp = T_next.translation() - T_prev.translation();
  return delta;
}

// What the analytic Jacobians need from one knot (double only; see spline/segment_jacobians.h):
// the derivatives of Omega_k = Log(T_{k-1}^-1 T_k) under the right perturbations
// T_k Exp(d_k), T_{k-1} Exp(d_{k-1}):
//     d Omega_k / d d_k     =  Jr^-1(Omega_k)     (Log(Exp(Omega) Exp(d)) ~ Omega + Jr^-1 d)
//     d Omega_k / d d_{k-1} = -Jl^-1(Omega_k)     (Log(Exp(-d) Exp(Omega)) ~ Omega - Jl^-1 d)
// Both are block upper-triangular [[D, U], [0, D]] (translation rows first) and stored as
// their two 3x3 blocks. M2..M5 are the rho-phi products of Barfoot's Q block, so that the
// right Jacobian of a scaled twist b Omega_k costs a few scalings (internal::ScaledQRight).
struct KnotDeltaJacobians {
  Eigen::Matrix3d Jr_inv_diag;   // Jr^-1(phi)
  Eigen::Matrix3d Jr_inv_upper;  // upper block of Jr^-1(Omega)
  Eigen::Matrix3d Jl_inv_diag;   // Jl^-1(phi)
  Eigen::Matrix3d Jl_inv_upper;  // upper block of Jl^-1(Omega)
  // Jr^-1(phi) = I + 1/2 P + c P^2 and Jl^-1(phi) = I - 1/2 P + c P^2 share c (lie/so3.h), so
  // G Jr^-1 and G Jl^-1 share G P and G P^2 (internal::ChainToControlPoses).
  double inv_c;
  Eigen::Matrix3d M2;  // P Rh + Rh P          (P = Hat(phi), Rh = Hat(rho))
  Eigen::Matrix3d M3;  // P Rh P
  Eigen::Matrix3d M4;  // P P Rh + Rh P P
  Eigen::Matrix3d M5;  // P Rh P P + P P Rh P
};

namespace internal {

// Below this x^2 = |b phi|^2 [rad^2] (x < 0.1 rad) the exponential coefficients use their
// Taylor series, kept to x^8: the first dropped term is below x^10 / 11! < 3e-18 relative. Above
// it, the closed forms of c3, c4, c5 lose about eps / x^2 (c3, c4) and 120 eps / x^4 (c5) to
// cancellation: <= 2.2e-14, 2.2e-14 and 2.7e-10 relative at the threshold, on terms that are
// themselves O(x^2) .. O(x^4) of the result (absolute contribution ~1e-16).
inline constexpr double kExpSeriesThresholdSq = 1e-2;

// Coefficient functions of Exp and of the Jacobians at x = |b phi| (all even in x):
//   cos_half = cos(x/2),  h = sin(x/2)/x,
//   c1 = sin x / x,  c2 = (1 - cos x)/x^2,  c3 = (x - sin x)/x^3        (Exp, Jl, Jr of SO(3))
//   c4 = (x^2 + 2 cos x - 2)/(2 x^4),  c5 = (2x - 3 sin x + x cos x)/(2 x^5)    (Q block)
// Series: c1 = sum (-1)^k x^2k/(2k+1)!, c2 = sum (-1)^k x^2k/(2k+2)!, c3 = sum (-1)^k
// x^2k/(2k+3)!, c4 = sum_{k>=1} (-1)^(k+1) x^(2k-2)/(2k+2)!, c5 = sum_{k>=1} (-1)^(k+1) k
// x^(2k-2)/(2k+3)!. Closed forms via one sin/cos of x/2: c1 = 2 h cos_half, c2 = 2 h^2,
// c3 = (1 - c1)/x^2, c4 = (1/2 - c2)/x^2, c5 = (3 c3 - c2)/(2 x^2)
// (2x - 3 sin x + x cos x = x^3 (3 c3 - c2)).
template <typename T>
struct ExpCoefficients {
  T cos_half;
  T h;
  T c1;
  T c2;
  T c3;
  T c4;  // only when computed with_q
  T c5;  // only when computed with_q
};

template <typename T>
ExpCoefficients<T> ComputeExpCoefficients(const T& x_sq, bool with_q) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  ExpCoefficients<T> k;
  if (x_sq < T(kExpSeriesThresholdSq)) {
    const T x2 = x_sq;
    const T x4 = x2 * x2;
    const T x6 = x4 * x2;
    const T x8 = x4 * x4;
    // cos(x/2) = sum (-1)^k (x/2)^2k/(2k)!;  h = 1/2 sum (-1)^k (x/2)^2k/(2k+1)!.
    k.cos_half = T(1.0) - x2 / T(8.0) + x4 / T(384.0) - x6 / T(46080.0) + x8 / T(10321920.0);
    k.h = T(0.5) - x2 / T(48.0) + x4 / T(3840.0) - x6 / T(645120.0) + x8 / T(185794560.0);
    k.c1 = T(1.0) - x2 / T(6.0) + x4 / T(120.0) - x6 / T(5040.0) + x8 / T(362880.0);
    k.c2 = T(0.5) - x2 / T(24.0) + x4 / T(720.0) - x6 / T(40320.0) + x8 / T(3628800.0);
    k.c3 = T(1.0 / 6.0) - x2 / T(120.0) + x4 / T(5040.0) - x6 / T(362880.0) + x8 / T(39916800.0);
    if (with_q) {
      k.c4 =
          T(1.0 / 24.0) - x2 / T(720.0) + x4 / T(40320.0) - x6 / T(3628800.0) + x8 / T(479001600.0);
      k.c5 = T(1.0 / 120.0) - x2 / T(2520.0) + x4 / T(120960.0) - x6 / T(9979200.0) +
             x8 / T(1245404160.0);
    }
    return k;
  }
  const T x = sqrt(x_sq);
  const T half = T(0.5) * x;
  k.cos_half = cos(half);
  k.h = sin(half) / x;
  k.c1 = T(2.0) * k.h * k.cos_half;
  k.c2 = T(2.0) * k.h * k.h;
  k.c3 = (T(1.0) - k.c1) / x_sq;
  if (with_q) {
    k.c4 = (T(0.5) - k.c2) / x_sq;
    k.c5 = (T(3.0) * k.c3 - k.c2) / (T(2.0) * x_sq);
  }
  return k;
}

// s I + a Hat(phi) + d Hat(phi)^2 entry by entry, with Hat(phi)^2 = phi phi^T - |phi|^2 I
// (theta_sq = |phi|^2): every SO(3) function of one rotation vector has this shape (Exp, the
// Jacobians, their products with each other), so it costs a few multiplications, no 3x3 product.
// Written in place (a returned matrix, copied by vector loads right after scalar stores, stalls
// on store forwarding when the call is not inlined).
template <typename T>
void SetIdentityHatSquare(
    const T& s, const T& a, const T& d, const Vector3<T>& phi, const T& theta_sq, Matrix3<T>* m) {
  const T diag = s - d * theta_sq;
  const T d01 = d * phi(0) * phi(1);
  const T d02 = d * phi(0) * phi(2);
  const T d12 = d * phi(1) * phi(2);
  const Vector3<T> a_phi = a * phi;
  // clang-format off
  *m << diag + d * phi(0) * phi(0), d01 - a_phi(2),              d02 + a_phi(1),
        d01 + a_phi(2),             diag + d * phi(1) * phi(1),  d12 - a_phi(0),
        d02 - a_phi(1),             d12 + a_phi(0),              diag + d * phi(2) * phi(2);
  // clang-format on
}

// A_j = Exp(b Omega_k) for one knot delta, with the pieces later steps reuse.
template <typename T>
struct ScaledExp {
  T b;
  ExpCoefficients<T> k;    // at x^2 = b^2 |phi|^2
  Eigen::Quaternion<T> q;  // rotation of A
  Matrix3<T> R;            // rotation of A
  Vector3<T> t;            // translation of A (set only when with_translation)
};

template <typename T>
void ComputeScaledExp(
    const KnotDelta<T>& delta, const T& b, bool with_translation, bool with_q, ScaledExp<T>* A) {
  A->b = b;
  A->k = ComputeExpCoefficients(b * b * delta.theta_sq, with_q);
  const Vector3<T>& phi = delta.phi;
  // R = I + b c1 Hat(phi) + b^2 c2 Hat(phi)^2.
  const T d = b * b * A->k.c2;
  SetIdentityHatSquare(T(1.0), b * A->k.c1, d, phi, delta.theta_sq, &A->R);
  const T bh = b * A->k.h;
  A->q = Eigen::Quaternion<T>(A->k.cos_half, bh * phi(0), bh * phi(1), bh * phi(2));
  if (with_translation) {
    A->t = b * delta.rho + d * delta.phi_x_rho + (b * b * b * A->k.c3) * delta.phi_x_phi_x_rho;
  }
}

}  // namespace internal

// A read-only view of what one segment needs: its first control pose P_0 = T_{i-1} (pose and
// rotation matrix), the rotation matrices of P_1..P_3 where the Jacobian caches exist (the split
// model's position Jacobians read them: spline/split_segment_jacobians.h) and the three knot
// deltas Omega_i, Omega_{i+1}, Omega_{i+2} (contiguous), plus their Jacobian caches (double only,
// may be null). Views point into an SE3Spline or a SegmentKnotData and are valid while that
// object is alive and unchanged.
template <typename T>
struct SegmentKnots {
  int first_index = 0;                            // index of P_0 in the spline
  const SE3<T>* T_first = nullptr;                // P_0
  const Matrix3<T>* R_first = nullptr;            // [1], or [4] with the Jacobian caches
  const KnotDelta<T>* deltas = nullptr;           // [3]
  const KnotDeltaJacobians* jacobians = nullptr;  // [3] or nullptr
};

template <typename T>
KnotDeltaJacobians MakeKnotDeltaJacobians(const KnotDelta<T>& delta);

// The knot data of one segment computed from its four control poses P_0..P_3 (for cost
// functions that receive the four pose blocks, e.g. under automatic differentiation). The
// Jacobian caches (and the rotation matrices of P_1..P_3) are filled only for T = double and
// with_jacobians.
template <typename T>
class SegmentKnotData {
 public:
  SegmentKnotData(const SE3<T>& P0,
                  const SE3<T>& P1,
                  const SE3<T>& P2,
                  const SE3<T>& P3,
                  bool with_jacobians = true,
                  int first_index = 0)
      : first_index_(first_index), T_first_(P0) {
    R_[0] = P0.so3().matrix();
    deltas_[0] = MakeKnotDelta(P0, P1);
    deltas_[1] = MakeKnotDelta(P1, P2);
    deltas_[2] = MakeKnotDelta(P2, P3);
    if constexpr (std::is_same_v<T, double>) {
      has_jacobians_ = with_jacobians;
      if (with_jacobians) {
        for (int j = 0; j < 3; ++j) jacobians_[j] = MakeKnotDeltaJacobians(deltas_[j]);
        R_[1] = P1.so3().matrix();
        R_[2] = P2.so3().matrix();
        R_[3] = P3.so3().matrix();
      }
    }
  }

  SegmentKnots<T> knots() const {
    SegmentKnots<T> view;
    view.first_index = first_index_;
    view.T_first = &T_first_;
    view.R_first = R_.data();
    view.deltas = deltas_.data();
    view.jacobians = has_jacobians_ ? jacobians_.data() : nullptr;
    return view;
  }

 private:
  int first_index_;
  SE3<T> T_first_;
  std::array<Matrix3<T>, kSplineOrder> R_;  // rotation matrices of P_0 (P_1..P_3: see above)
  std::array<KnotDelta<T>, 3> deltas_;
  std::array<KnotDeltaJacobians, 3> jacobians_;
  bool has_jacobians_ = false;
};

namespace internal {

// Everything the forward pass computes, kept for the Jacobians (segment_jacobians.h). Index j-1
// holds step j = 1..3. Entries are set only when the flags asked for them.
template <typename T>
struct SegmentTrace {
  std::array<ScaledExp<T>, 3> A;
  // xi_j = [v; w], alpha_j = [av; aw]; y_j = Ad(A_j^-1) xi_{j-1}, z_j = Ad(A_j^-1) alpha_{j-1}.
  std::array<Vector3<T>, 3> v, w, av, aw;
  std::array<Vector3<T>, 3> yv, yw, zv, zw;
};

struct TraceRequest {
  bool translation = false;     // t(A_j): pose translation or linear rates
  bool rates = false;           // xi / w recursion
  bool linear = false;          // linear part of the recursion (v, av)
  bool acceleration = false;    // alpha recursion
  bool q_coefficients = false;  // c4, c5 for the SE(3) Q block (Jacobians)
};

// The forward pass: the three scaled exponentials and the twist recursion.
template <typename T>
void ForwardPass(const SegmentKnots<T>& knots,
                 const Segment<T>& segment,
                 const TraceRequest& request,
                 SegmentTrace<T>* trace) {
  for (int j = 0; j < 3; ++j) {
    ComputeScaledExp(knots.deltas[j],
                     segment.b[j + 1],
                     request.translation || request.linear,
                     request.q_coefficients,
                     &trace->A[j]);
  }
  if (!request.rates) return;
  const bool linear = request.linear;
  const bool acceleration = request.acceleration;
  // Step 1: xi_0 = alpha_0 = 0.
  {
    const KnotDelta<T>& delta = knots.deltas[0];
    const T& bd = segment.b_dot[1];
    const T& bdd = segment.b_ddot[1];
    trace->w[0] = bd * delta.phi;
    if (linear) trace->v[0] = bd * delta.rho;
    if (acceleration) {
      trace->aw[0] = bdd * delta.phi;
      if (linear) trace->av[0] = bdd * delta.rho;
    }
  }
  // Steps 2, 3: [Sommer20] recursion (see the header comment).
  for (int j = 1; j < 3; ++j) {
    const KnotDelta<T>& delta = knots.deltas[j];
    const ScaledExp<T>& A = trace->A[j];
    const T& bd = segment.b_dot[j + 1];
    const T& bdd = segment.b_ddot[j + 1];
    const Matrix3<T> Rt = A.R.transpose();
    trace->yw[j] = Rt * trace->w[j - 1];
    trace->w[j] = trace->yw[j] + bd * delta.phi;
    if (linear) {
      trace->yv[j] = Rt * (trace->v[j - 1] - A.t.cross(trace->w[j - 1]));
      trace->v[j] = trace->yv[j] + bd * delta.rho;
    }
    if (acceleration) {
      trace->zw[j] = Rt * trace->aw[j - 1];
      trace->aw[j] = trace->zw[j] + bd * trace->yw[j].cross(delta.phi) + bdd * delta.phi;
      if (linear) {
        trace->zv[j] = Rt * (trace->av[j - 1] - A.t.cross(trace->aw[j - 1]));
        trace->av[j] = trace->zv[j] +
                       bd * (trace->yw[j].cross(delta.rho) + trace->yv[j].cross(delta.phi)) +
                       bdd * delta.rho;
      }
    }
  }
}

// R_w_s = R_0 R_1 R_2 R_3.
template <typename T>
Matrix3<T> SegmentRotation(const SegmentKnots<T>& knots, const SegmentTrace<T>& trace) {
  return (*knots.R_first) * (trace.A[0].R * (trace.A[1].R * trace.A[2].R));
}

// R_w_s^T x_w = R_3^T R_2^T R_1^T R_0^T x_w (four matrix-vector products).
template <typename T>
Vector3<T> RotateToBody(const SegmentKnots<T>& knots,
                        const SegmentTrace<T>& trace,
                        const Vector3<T>& x_w) {
  const Vector3<T> x_0 = knots.R_first->transpose() * x_w;
  const Vector3<T> x_1 = trace.A[0].R.transpose() * x_0;
  const Vector3<T> x_2 = trace.A[1].R.transpose() * x_1;
  return trace.A[2].R.transpose() * x_2;
}

// q(R_w_s) = q(P_0) q(A_1) q(A_2) q(A_3): the orientation, the same in both trajectory models.
template <typename T>
Eigen::Quaternion<T> SegmentQuaternion(const SegmentKnots<T>& knots, const SegmentTrace<T>& trace) {
  return knots.T_first->so3().quaternion() * trace.A[0].q * trace.A[1].q * trace.A[2].q;
}

// T_w_s = P_0 A_1 A_2 A_3 (quaternion product for the rotation; needs the translations).
template <typename T>
SE3<T> SegmentPose(const SegmentKnots<T>& knots, const SegmentTrace<T>& trace) {
  const Eigen::Quaternion<T> q = SegmentQuaternion(knots, trace);
  const Vector3<T> t_123 =
      trace.A[0].t + trace.A[0].R * (trace.A[1].t + trace.A[1].R * trace.A[2].t);
  return SE3<T>(SO3<T>(q), knots.T_first->translation() + (*knots.R_first) * t_123);
}

// The body-frame form of every output (nullptr = not wanted, skipped):
//   T_w_s, R_w_s (rotation matrix), w_s, w_dot_s (body angular velocity / acceleration),
//   v_s = R_w_s^T dp_w_s/dt, a_s = R_w_s^T d2p_w_s/dt2.
template <typename T>
void EvaluateSegmentBody(const SegmentKnots<T>& knots,
                         const Segment<T>& segment,
                         NonDeducedT<SE3<T>>* T_w_s,
                         NonDeducedT<Matrix3<T>>* R_w_s,
                         NonDeducedT<Vector3<T>>* w_s,
                         NonDeducedT<Vector3<T>>* w_dot_s,
                         NonDeducedT<Vector3<T>>* v_s,
                         NonDeducedT<Vector3<T>>* a_s) {
  TraceRequest request;
  request.translation = T_w_s != nullptr;
  request.linear = v_s != nullptr || a_s != nullptr;
  request.rates = request.linear || w_s != nullptr || w_dot_s != nullptr;
  request.acceleration = a_s != nullptr || w_dot_s != nullptr;
  SegmentTrace<T> trace;
  ForwardPass(knots, segment, request, &trace);
  if (T_w_s != nullptr) *T_w_s = SegmentPose(knots, trace);
  if (R_w_s != nullptr) *R_w_s = SegmentRotation(knots, trace);
  if (w_s != nullptr) *w_s = trace.w[2];
  if (w_dot_s != nullptr) *w_dot_s = trace.aw[2];
  if (v_s != nullptr) *v_s = trace.v[2];
  if (a_s != nullptr) *a_s = trace.av[2] + trace.w[2].cross(trace.v[2]);
}

}  // namespace internal

// Evaluates the segment at `segment` in one pass. Every output is optional (nullptr = not
// wanted; the work for it is skipped):
//   T_w_s    pose of the IMU/body frame s in the world w
//   w_s      body angular velocity vee(R_w_s^T dR_w_s/dt)            [rad/s]
//   w_dot_s  body angular acceleration dw_s/dt                       [rad/s^2]
//   v_w      world linear velocity dp_w_s/dt                         [m/s]
//   a_w      world linear acceleration d2p_w_s/dt2                   [m/s^2]
// All analytic (header comment); no finite differences.
template <typename T>
void EvaluateSegment(const SegmentKnots<T>& knots,
                     const Segment<T>& segment,
                     internal::NonDeducedT<SE3<T>>* T_w_s,
                     internal::NonDeducedT<Vector3<T>>* w_s = nullptr,
                     internal::NonDeducedT<Vector3<T>>* w_dot_s = nullptr,
                     internal::NonDeducedT<Vector3<T>>* v_w = nullptr,
                     internal::NonDeducedT<Vector3<T>>* a_w = nullptr) {
  const bool linear = v_w != nullptr || a_w != nullptr;
  Matrix3<T> R_w_s;
  Vector3<T> v_s;
  Vector3<T> a_s;
  internal::EvaluateSegmentBody(knots,
                                segment,
                                T_w_s,
                                linear ? &R_w_s : nullptr,
                                w_s,
                                w_dot_s,
                                v_w != nullptr ? &v_s : nullptr,
                                a_w != nullptr ? &a_s : nullptr);
  if (v_w != nullptr) *v_w = R_w_s * v_s;
  if (a_w != nullptr) *a_w = R_w_s * a_s;
}

namespace internal {

// Right Jacobian of SE(3) at a scaled twist b Omega, as the block pair (diag, upper) of
// b * Jr(b Omega) = b [[Jr(b phi), Qr(b rho, b phi)], [0, Jr(b phi)]]  (the factor b included:
// it is d/dOmega of the right tangent of Exp(b Omega)):
//   b Jr(b phi)  = b I - b^2 c2 P + b^3 c3 P^2
//   Qr(b rho, b phi) = Ql(-b rho, -b phi)
//     = -b/2 Rh + c3 b^2 M2 - c3 b^3 M3 - c4 b^3 (M4 - 3 M3) + c5 b^4 M5
// from Barfoot's Q (lie/se3.h, internal::SE3QBlock) with each product of k hats scaled by b^k
// and odd products sign-flipped. c's are at x = |b phi| (ExpCoefficients).
inline void ScaledRightJacobianSO3(const KnotDelta<double>& delta,
                                   const ScaledExp<double>& A,
                                   Eigen::Matrix3d* b_Jr) {
  const double b = A.b;
  // b I - b^2 c2 Hat(phi) + b^3 c3 Hat(phi)^2.
  SetIdentityHatSquare(b, -(b * b * A.k.c2), b * b * b * A.k.c3, delta.phi, delta.theta_sq, b_Jr);
}

inline Eigen::Matrix3d ScaledQRight(const KnotDelta<double>& delta,
                                    const KnotDeltaJacobians& J,
                                    const ScaledExp<double>& A) {
  const double b = A.b;
  const double b2 = b * b;
  const double b3 = b2 * b;
  const double b4 = b2 * b2;
  const double c3 = A.k.c3;
  const double c4 = A.k.c4;
  const double c5 = A.k.c5;
  Eigen::Matrix3d Q =
      (c3 * b2) * J.M2 + ((3.0 * c4 - c3) * b3) * J.M3 - (c4 * b3) * J.M4 + (c5 * b4) * J.M5;
  const Eigen::Vector3d half_rho = (0.5 * b) * delta.rho;  // -b/2 Hat(rho)
  Q(0, 1) += half_rho(2);
  Q(0, 2) -= half_rho(1);
  Q(1, 0) -= half_rho(2);
  Q(1, 2) += half_rho(0);
  Q(2, 0) += half_rho(1);
  Q(2, 1) -= half_rho(0);
  return Q;
}

}  // namespace internal

template <typename T>
KnotDeltaJacobians MakeKnotDeltaJacobians(const KnotDelta<T>& delta) {
  static_assert(std::is_same_v<T, double>, "Jacobian caches exist for double splines only");
  KnotDeltaJacobians J;
  const Eigen::Matrix3d P = Hat(delta.phi);
  const Eigen::Matrix3d Rh = Hat(delta.rho);
  const Eigen::Matrix3d PR = P * Rh;
  const Eigen::Matrix3d RP = Rh * P;
  J.M2 = PR + RP;
  J.M3 = PR * P;
  J.M4 = P * PR + RP * P;
  J.M5 = J.M3 * P + P * J.M3;
  // Barfoot's Q at b = 1 for Omega (left) and -Omega (right): odd products flip sign.
  internal::ScaledExp<double> A;
  A.b = 1.0;
  A.k = internal::ComputeExpCoefficients(delta.theta_sq, true);
  const Eigen::Matrix3d Q_right = internal::ScaledQRight(delta, J, A);
  const Eigen::Matrix3d Q_left =
      0.5 * Rh + A.k.c3 * J.M2 + (A.k.c3 - 3.0 * A.k.c4) * J.M3 + A.k.c4 * J.M4 + A.k.c5 * J.M5;
  // Jr^-1(Omega) = [[Jr^-1, -Jr^-1 Qr Jr^-1], [0, Jr^-1]] (block inverse of Jr; lie/se3.h).
  J.inv_c = internal::ComputeSO3JacobianCoefficients(delta.theta_sq, true).c;
  J.Jr_inv_diag = RightJacobianInverseSO3(delta.phi);
  J.Jl_inv_diag = LeftJacobianInverseSO3(delta.phi);
  J.Jr_inv_upper = -J.Jr_inv_diag * Q_right * J.Jr_inv_diag;
  J.Jl_inv_upper = -J.Jl_inv_diag * Q_left * J.Jl_inv_diag;
  return J;
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_SEGMENT_H_
