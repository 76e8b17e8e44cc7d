// A reference trajectory model for the benchmarks (bench/spline_vs_reference_bench.cc): the
// "split" spline of basalt-headers' Se3Spline, written here from the published formulas so that
// splinecal's coupled SE(3) spline can be timed against it in one binary (docs/performance.md). Not
// part of the library; header-only; its own SO(3) helpers so that it shares no code with splinecal.
//
// Model. Rotation control points R_k and position control points p_k, k = 0..n-1, at knot times
// t_k = t0 + k dt. For t in [t_i, t_{i+1}), u = (t - t_i) / dt, with the cumulative coefficients
// b_j = Bt_j(u) of docs/conventions.md "The spline" (j = 1..3) and the segment's control points
// R_0..R_3 = R_{i-1}..R_{i+2} (likewise p):
//
//     R(t) = R_0 A_1 A_2 A_3,   A_j = Exp(b_j phi_j),   phi_j = Log(R_{j-1}^T R_j)
//                                                         (SO(3) cumulative spline, [Kim95])
//     p(t) = p_0 + sum_j b_j (p_j - p_{j-1})              (R^3 cubic B-spline, cumulative form)
//
// The rotation is exactly the rotation part of splinecal's coupled spline evaluated on the same
// control rotations (the rotation of Exp([rho; phi]) is Exp(phi)), so the body angular velocity
// agrees with splinecal's; the position does not (the coupled spline blends translations through
// the rotations).
//
// Derivatives ([Sommer20] Theorem 1, on SO(3)): with w the body angular velocity of the
// partial product R_0 A_1 .. A_j,
//     w_1 = bdot_1 phi_1,   w_j = A_j^T w_{j-1} + bdot_j phi_j,   w_s = w_3,
//     a_w = sum_j bddot_j (p_j - p_{j-1}).
//
// Jacobians. Control point k is perturbed as R_k Exp(dphi_k) (right, as splinecal) and
// p_k + dp_k (additive in the world, as basalt); a Jacobian block is 3x6 [d/dp_k | d/dphi_k].
//   * Knot deltas (Log(Exp(phi) Exp(d)) ~ phi + Jr^-1 d, Log(Exp(-d) Exp(phi)) ~ phi - Jl^-1 d):
//       d phi_j = Jr^-1(phi_j) dphi_j - Jl^-1(phi_j) dphi_{j-1},
//       Jr^-1(phi) = I + P/2 + e P^2,  Jl^-1(phi) = I - P/2 + e P^2   (P = [phi]x,
//       e = 1/x^2 - (1 + cos x) / (2 x sin x), x = |phi|).
//   * Scaled exponential: Exp(b (phi + d)) = Exp(b phi) Exp(b Jr(b phi) d),
//       b Jr(b phi) = b I - b^2 c2 P + b^3 c3 P^2   (c2 = (1 - cos y)/y^2, c3 = (y - sin y)/y^3,
//       y = |b phi|).
//   * Gyro: d(A^T x) / d phi = [A^T x]x b Jr(b phi). Hence K_j = d w_s / d phi_j:
//       K_3 = [y_3]x bJr_3 + bdot_3 I,  K_2 = A_3^T ([y_2]x bJr_2 + bdot_2 I),
//       K_1 = bdot_1 A_3^T A_2^T,       y_j = A_j^T w_{j-1},
//     block k = K_k Jr^-1(phi_k) - K_{k+1} Jl^-1(phi_{k+1}) (terms that exist).
//   * Rotation of the pose: d phi_R = X_0^T dphi_0 + sum_j X_j^T bJr_j d phi_j with
//     X_j = A_{j+1} .. A_3 (X_3 = I).
//   * Accelerometer f = R^T (a_w - g) + b_a: d f / d phi_R = [f - b_a]x, so with
//     G_0 = [f - b_a]x X_0^T and G_j = [f - b_a]x X_j^T bJr_j, rotation block
//     k = G_k Jr^-1(phi_k) - G_{k+1} Jl^-1(phi_{k+1}) (G_0 itself for k = 0); translation block
//     k = beta_k R^T with beta = (-bddot_1, bddot_1 - bddot_2, bddot_2 - bddot_3, bddot_3).
//     d f / d b_a = I, d f / d g = -R^T.
//
// Two ways to get the knot deltas, both timed: KnotMode::kPerQuery computes the three Logs (and
// the e's) in every evaluation, as basalt-headers' Se3Spline does; KnotMode::kCached computes
// them once per knot, as splinecal's SE3Spline does.
//
// References ([Sommer20] is in docs/references.md; [Kim95] is cited here only)
//   [Sommer20] C. Sommer, V. Usenko, D. Schubert, N. Demmel, D. Cremers, "Efficient Derivative
//              Computation for Cumulative B-Splines on Lie Groups", CVPR 2020.
//   [Kim95]    M.-J. Kim, M.-S. Kim, S. Y. Shin, "A General Construction Scheme for Unit
//              Quaternion Curves with Simple High Order Derivatives", SIGGRAPH 1995.
#ifndef SPLINECAL_TESTS_SPLINE_REFERENCE_SPLIT_SPLINE_H_
#define SPLINECAL_TESTS_SPLINE_REFERENCE_SPLIT_SPLINE_H_

#include <glog/logging.h>

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>
#include <vector>

namespace splinecal {
namespace reference {

// ---- SO(3) pieces, written for this file ----

inline Eigen::Matrix3d Skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0.0, -v(2), v(1), v(2), 0.0, -v(0), -v(1), v(0), 0.0;
  return m;
}

// M [v]x, column by column (column c of [v]x is v x e_c).
inline Eigen::Matrix3d TimesSkew(const Eigen::Matrix3d& M, const Eigen::Vector3d& v) {
  Eigen::Matrix3d out;
  out.col(0) = v(2) * M.col(1) - v(1) * M.col(2);
  out.col(1) = v(0) * M.col(2) - v(2) * M.col(0);
  out.col(2) = v(1) * M.col(0) - v(0) * M.col(1);
  return out;
}

// s I + a [v]x + d [v]x^2, with [v]x^2 = v v^T - |v|^2 I.
inline Eigen::Matrix3d IdentitySkewSquare(double s, double a, double d, const Eigen::Vector3d& v) {
  const double diag = s - d * v.squaredNorm();
  Eigen::Matrix3d m;
  m(0, 0) = diag + d * v(0) * v(0);
  m(1, 1) = diag + d * v(1) * v(1);
  m(2, 2) = diag + d * v(2) * v(2);
  m(0, 1) = d * v(0) * v(1) - a * v(2);
  m(1, 0) = d * v(0) * v(1) + a * v(2);
  m(0, 2) = d * v(0) * v(2) + a * v(1);
  m(2, 0) = d * v(0) * v(2) - a * v(1);
  m(1, 2) = d * v(1) * v(2) - a * v(0);
  m(2, 1) = d * v(1) * v(2) + a * v(0);
  return m;
}

// sin y / y, (1 - cos y)/y^2, (y - sin y)/y^3 at y^2 = y_sq; Taylor series below y = 0.1, kept to
// y^8 (the first dropped term is below y^10 / 11! = 2.5e-18 at the switch), closed forms above.
struct RotationCoefficients {
  double c1;
  double c2;
  double c3;
};

inline RotationCoefficients ComputeRotationCoefficients(double y_sq) {
  RotationCoefficients c;
  if (y_sq < 1e-2) {
    const double y4 = y_sq * y_sq;
    const double y6 = y4 * y_sq;
    const double y8 = y4 * y4;
    c.c1 = 1.0 - y_sq / 6.0 + y4 / 120.0 - y6 / 5040.0 + y8 / 362880.0;
    c.c2 = 0.5 - y_sq / 24.0 + y4 / 720.0 - y6 / 40320.0 + y8 / 3628800.0;
    c.c3 = 1.0 / 6.0 - y_sq / 120.0 + y4 / 5040.0 - y6 / 362880.0 + y8 / 39916800.0;
    return c;
  }
  const double y = std::sqrt(y_sq);
  const double s = std::sin(y);
  const double co = std::cos(y);
  c.c1 = s / y;
  c.c2 = (1.0 - co) / y_sq;
  c.c3 = (1.0 - c.c1) / y_sq;
  return c;
}

// Log of a rotation matrix: x = atan2(sin, cos) from the skew and trace parts; near pi the axis
// comes from the symmetric part (R + R^T)/2 - cos I = (1 - cos) n n^T.
inline Eigen::Vector3d LogRotation(const Eigen::Matrix3d& R) {
  const Eigen::Vector3d two_sin_n(R(2, 1) - R(1, 2), R(0, 2) - R(2, 0), R(1, 0) - R(0, 1));
  const double cos_x = 0.5 * (R.trace() - 1.0);
  const double sin_x = 0.5 * two_sin_n.norm();
  const double x = std::atan2(sin_x, cos_x);
  if (cos_x > -0.99) {
    // x / (2 sin x): series 1/2 (1 + x^2/6 + 7 x^4/360) below x^2 = 1e-4 (next term 31 x^6/15120).
    const double x_sq = x * x;
    const double factor =
        x_sq < 1e-4 ? 0.5 * (1.0 + x_sq / 6.0 + 7.0 * x_sq * x_sq / 360.0) : 0.5 * x / sin_x;
    return factor * two_sin_n;
  }
  const Eigen::Matrix3d B = 0.5 * (R + R.transpose()) - cos_x * Eigen::Matrix3d::Identity();
  int k = 0;
  B.diagonal().maxCoeff(&k);
  Eigen::Vector3d n = B.col(k) / std::sqrt(B(k, k) * (1.0 - cos_x));
  if (n.dot(two_sin_n) < 0.0) n = -n;
  return x * n;
}

// e of Jr^-1(phi) = I + P/2 + e P^2 at x^2 = |phi|^2; series below x = 0.1 (to x^6).
inline double InverseJacobianCoefficient(double x_sq) {
  if (x_sq < 1e-2) {
    return 1.0 / 12.0 + x_sq / 720.0 + x_sq * x_sq / 30240.0 + x_sq * x_sq * x_sq / 1209600.0;
  }
  const double x = std::sqrt(x_sq);
  return 1.0 / x_sq - (1.0 + std::cos(x)) / (2.0 * x * std::sin(x));
}

// ---- the spline ----

// Where a time falls: segment i (control points i-1 .. i+2), u, and the cumulative coefficients
// with their time derivatives (entries 1..3; entry 0 is Bt_0 = 1 and unused).
struct Query {
  int index = 1;
  double u = 0.0;
  std::array<double, 4> b{};
  std::array<double, 4> b_dot{};
  std::array<double, 4> b_ddot{};
};

// d/du of the cumulative basis C [1 u u^2 u^3]^T, C of docs/conventions.md "The spline", written
// out per row.
inline Query MakeQuery(int index, double u, double dt_s) {
  const double u2 = u * u;
  const double u3 = u2 * u;
  const double inv_dt = 1.0 / dt_s;
  const double inv_dt2 = inv_dt * inv_dt;
  Query q;
  q.index = index;
  q.u = u;
  q.b = {1.0,
         (5.0 + 3.0 * u - 3.0 * u2 + u3) / 6.0,
         (1.0 + 3.0 * u + 3.0 * u2 - 2.0 * u3) / 6.0,
         u3 / 6.0};
  q.b_dot = {0.0, 0.5 * (1.0 - u) * (1.0 - u) * inv_dt, (0.5 + u - u2) * inv_dt, 0.5 * u2 * inv_dt};
  q.b_ddot = {0.0, (u - 1.0) * inv_dt2, (1.0 - 2.0 * u) * inv_dt2, u * inv_dt2};
  return q;
}

enum class KnotMode { kPerQuery, kCached };

// 3x6 blocks [d/dp_k | d/dphi_k] for the four control points of the segment, plus the bias and
// (accelerometer) gravity blocks.
struct ResidualJacobians {
  std::array<Eigen::Matrix<double, 3, 6>, 4> control;
  Eigen::Matrix3d bias;
  Eigen::Matrix3d gravity;
};

class SplitSpline {
 public:
  SplitSpline(std::vector<Eigen::Matrix3d> rotations,
              std::vector<Eigen::Vector3d> positions,
              int64_t t0_ns,
              int64_t dt_ns,
              KnotMode mode)
      : R_(std::move(rotations)),
        p_(std::move(positions)),
        t0_ns_(t0_ns),
        dt_ns_(dt_ns),
        dt_s_(1e-9 * static_cast<double>(dt_ns)),
        mode_(mode) {
    CHECK_GE(R_.size(), 4u);
    CHECK_EQ(R_.size(), p_.size());
    CHECK_GT(dt_ns, 0);
    if (mode_ == KnotMode::kCached) {
      phi_.resize(R_.size());
      e_.resize(R_.size());
      dp_.resize(R_.size());
      for (size_t k = 1; k < R_.size(); ++k) {
        phi_[k] = LogRotation(R_[k - 1].transpose() * R_[k]);
        e_[k] = InverseJacobianCoefficient(phi_[k].squaredNorm());
        dp_[k] = p_[k] - p_[k - 1];
      }
    }
  }

  // Valid times [t_1, t_{n-2}]; the end evaluates the last segment at u = 1.
  Query QueryAtNs(int64_t t_ns) const {
    const int64_t offset = t_ns - t0_ns_;
    CHECK(offset >= dt_ns_ && offset <= (static_cast<int64_t>(R_.size()) - 2) * dt_ns_)
        << "time outside the spline";
    int index = static_cast<int>(offset / dt_ns_);
    int64_t rest = offset - index * dt_ns_;
    if (index == static_cast<int>(R_.size()) - 2) {
      --index;
      rest = dt_ns_;
    }
    return MakeQuery(index, static_cast<double>(rest) / static_cast<double>(dt_ns_), dt_s_);
  }

  double dt_s() const { return dt_s_; }

  // R(t), p(t).
  void Pose(const Query& q, Eigen::Matrix3d* R, Eigen::Vector3d* p) const {
    const Knots k = GatherKnots(q, false);
    Forward f;
    Exponentials(k, q, false, &f);
    *R = (*k.R0 * f.A[0]) * (f.A[1] * f.A[2]);
    *p = *k.p0 + q.b[1] * k.dp[0] + q.b[2] * k.dp[1] + q.b[3] * k.dp[2];
  }

  // Body angular velocity w_s and world acceleration a_w (what an IMU prediction needs besides R).
  void Rates(const Query& q, Eigen::Vector3d* w_s, Eigen::Vector3d* a_w) const {
    const Knots k = GatherKnots(q, false);
    Forward f;
    Exponentials(k, q, false, &f);
    AngularVelocity(k, q, &f);
    *w_s = f.w3;
    *a_w = Acceleration(k, q);
  }

  // Predicted gyro w_s + b_g and accelerometer R^T (a_w - g) + b_a in one pass.
  void PredictImu(const Query& q,
                  const Eigen::Vector3d& g_w,
                  const Eigen::Vector3d& b_g,
                  const Eigen::Vector3d& b_a,
                  Eigen::Vector3d* gyro,
                  Eigen::Vector3d* accel) const {
    const Knots k = GatherKnots(q, false);
    Forward f;
    Exponentials(k, q, false, &f);
    AngularVelocity(k, q, &f);
    *gyro = f.w3 + b_g;
    const Eigen::Vector3d x = Acceleration(k, q) - g_w;
    *accel =
        f.A[2].transpose() * (f.A[1].transpose() * (f.A[0].transpose() * (k.R0->transpose() * x))) +
        b_a;
  }

  // r = w_s + b_g - measured and its Jacobians (translation columns zero).
  void GyroResidual(const Query& q,
                    const Eigen::Vector3d& measured,
                    const Eigen::Vector3d& b_g,
                    Eigen::Vector3d* residual,
                    ResidualJacobians* J) const {
    const Knots k = GatherKnots(q, J != nullptr);
    Forward f;
    Exponentials(k, q, J != nullptr, &f);
    AngularVelocity(k, q, &f);
    *residual = f.w3 + b_g - measured;
    if (J == nullptr) return;
    std::array<Eigen::Matrix3d, 4> K;  // K[j] = d w_s / d phi_j, j = 1..3 (K[0] unused)
    K[3] = TimesSkewLeft(f.y3, f.bJr[2]);
    K[3].diagonal().array() += q.b_dot[3];
    Eigen::Matrix3d inner = TimesSkewLeft(f.y2, f.bJr[1]);
    inner.diagonal().array() += q.b_dot[2];
    const Eigen::Matrix3d A3t = f.A[2].transpose();
    K[2].noalias() = A3t * inner;
    K[1].noalias() = (q.b_dot[1] * A3t) * f.A[1].transpose();
    K[0].setZero();
    std::array<Eigen::Matrix3d, 4> rotation_blocks;
    ChainToControlPoints(k, K, &rotation_blocks);
    for (int c = 0; c < 4; ++c) {
      J->control[c].leftCols<3>().setZero();
      J->control[c].rightCols<3>() = rotation_blocks[c];
    }
    J->bias.setIdentity();
  }

  // r = R^T (a_w - g_w) + b_a - measured and its Jacobians.
  void AccelResidual(const Query& q,
                     const Eigen::Vector3d& measured,
                     const Eigen::Vector3d& b_a,
                     const Eigen::Vector3d& g_w,
                     Eigen::Vector3d* residual,
                     ResidualJacobians* J) const {
    const Knots k = GatherKnots(q, J != nullptr);
    Forward f;
    Exponentials(k, q, J != nullptr, &f);
    const Eigen::Matrix3d R = (*k.R0 * f.A[0]) * (f.A[1] * f.A[2]);
    const Eigen::Vector3d f0 = R.transpose() * (Acceleration(k, q) - g_w);
    *residual = f0 + b_a - measured;
    if (J == nullptr) return;
    // M_j = [f0]x X_j^T, from M_3 = [f0]x to M_0 = [f0]x A_3^T A_2^T A_1^T.
    std::array<Eigen::Matrix3d, 4> G;
    Eigen::Matrix3d M = Skew(f0);
    G[3].noalias() = M * f.bJr[2];
    M = M * f.A[2].transpose();
    G[2].noalias() = M * f.bJr[1];
    M = M * f.A[1].transpose();
    G[1].noalias() = M * f.bJr[0];
    G[0].noalias() = M * f.A[0].transpose();
    std::array<Eigen::Matrix3d, 4> rotation_blocks;
    ChainToControlPoints(k, G, &rotation_blocks);
    const Eigen::Matrix3d Rt = R.transpose();
    const std::array<double, 4> beta = {
        -q.b_ddot[1], q.b_ddot[1] - q.b_ddot[2], q.b_ddot[2] - q.b_ddot[3], q.b_ddot[3]};
    for (int c = 0; c < 4; ++c) {
      J->control[c].leftCols<3>() = beta[c] * Rt;
      J->control[c].rightCols<3>() = rotation_blocks[c];
    }
    J->bias.setIdentity();
    J->gravity = -Rt;
  }

 private:
  // The segment's control data: R_0, p_0 and the three knot deltas (with e when asked).
  struct Knots {
    const Eigen::Matrix3d* R0;
    const Eigen::Vector3d* p0;
    std::array<Eigen::Vector3d, 3> phi;
    std::array<Eigen::Vector3d, 3> dp;
    std::array<double, 3> e;
  };

  struct Forward {
    std::array<Eigen::Matrix3d, 3> A;    // Exp(b_j phi_j)
    std::array<Eigen::Matrix3d, 3> bJr;  // b_j Jr(b_j phi_j) (Jacobians only)
    Eigen::Vector3d y2, y3, w3;
  };

  Knots GatherKnots(const Query& q, bool with_e) const {
    const int first = q.index - 1;
    Knots k;
    k.R0 = &R_[first];
    k.p0 = &p_[first];
    for (int j = 0; j < 3; ++j) {
      const int knot = first + 1 + j;
      if (mode_ == KnotMode::kCached) {
        k.phi[j] = phi_[knot];
        k.dp[j] = dp_[knot];
        k.e[j] = e_[knot];
      } else {
        k.phi[j] = LogRotation(R_[knot - 1].transpose() * R_[knot]);
        k.dp[j] = p_[knot] - p_[knot - 1];
        if (with_e) k.e[j] = InverseJacobianCoefficient(k.phi[j].squaredNorm());
      }
    }
    return k;
  }

  static void Exponentials(const Knots& k, const Query& q, bool with_jr, Forward* f) {
    for (int j = 0; j < 3; ++j) {
      const double b = q.b[j + 1];
      const Eigen::Vector3d& phi = k.phi[j];
      const RotationCoefficients c = ComputeRotationCoefficients(b * b * phi.squaredNorm());
      f->A[j] = IdentitySkewSquare(1.0, b * c.c1, b * b * c.c2, phi);
      if (with_jr) f->bJr[j] = IdentitySkewSquare(b, -b * b * c.c2, b * b * b * c.c3, phi);
    }
  }

  static void AngularVelocity(const Knots& k, const Query& q, Forward* f) {
    const Eigen::Vector3d w1 = q.b_dot[1] * k.phi[0];
    f->y2 = f->A[1].transpose() * w1;
    const Eigen::Vector3d w2 = f->y2 + q.b_dot[2] * k.phi[1];
    f->y3 = f->A[2].transpose() * w2;
    f->w3 = f->y3 + q.b_dot[3] * k.phi[2];
  }

  static Eigen::Vector3d Acceleration(const Knots& k, const Query& q) {
    return q.b_ddot[1] * k.dp[0] + q.b_ddot[2] * k.dp[1] + q.b_ddot[3] * k.dp[2];
  }

  // [y]x M, column by column.
  static Eigen::Matrix3d TimesSkewLeft(const Eigen::Vector3d& y, const Eigen::Matrix3d& M) {
    Eigen::Matrix3d out;
    for (int c = 0; c < 3; ++c) out.col(c) = y.cross(M.col(c));
    return out;
  }

  // Block c = G[c] Jr^-1(phi_c) - G[c+1] Jl^-1(phi_{c+1}) (G[0] enters block 0 directly), with
  // G Jr^-1 = G + GP/2 + e GPP and G Jl^-1 = G - GP/2 + e GPP sharing GP and GPP.
  static void ChainToControlPoints(const Knots& k,
                                   const std::array<Eigen::Matrix3d, 4>& G,
                                   std::array<Eigen::Matrix3d, 4>* blocks) {
    (*blocks)[0] = G[0];
    for (int c = 1; c < 4; ++c) (*blocks)[c].setZero();
    for (int j = 1; j <= 3; ++j) {
      const Eigen::Vector3d& phi = k.phi[j - 1];
      const Eigen::Matrix3d GP = TimesSkew(G[j], phi);
      const Eigen::Matrix3d even = G[j] + k.e[j - 1] * TimesSkew(GP, phi);
      (*blocks)[j] += even + 0.5 * GP;
      (*blocks)[j - 1] -= even - 0.5 * GP;
    }
  }

  std::vector<Eigen::Matrix3d> R_;
  std::vector<Eigen::Vector3d> p_;
  int64_t t0_ns_;
  int64_t dt_ns_;
  double dt_s_;
  KnotMode mode_;
  std::vector<Eigen::Vector3d> phi_;  // [k] = Log(R_{k-1}^T R_k), k >= 1 (kCached)
  std::vector<double> e_;
  std::vector<Eigen::Vector3d> dp_;
};

}  // namespace reference
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_SPLINE_REFERENCE_SPLIT_SPLINE_H_
