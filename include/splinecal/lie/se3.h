// SE(3), the group of rigid-body motions, built from lie/so3.h.
//
// Conventions (binding for the whole library)
//   * T_a_b is the pose of frame b in frame a: p_a = R_a_b p_b + t_a_b (docs/conventions.md "Frames
//     and notation").
//   * Tangent vectors are xi = [rho; phi] in R^6, TRANSLATION FIRST (rho), rotation second (phi):
//       Hat(xi) = [[Hat(phi), rho], [0, 0]]  (4x4).
//   * ONE perturbation convention: RIGHT.  T (+) d = T * Exp(d),  d = [rho; phi].
//     Every Jacobian with respect to a pose in splinecal is d f(T Exp(d)) / d d at d = 0, and
//     lie/se3_manifold.h (the Ceres manifold of a pose block) retracts the same way.
//
// What this header implements
//   SE3<T>           a pose: an SO3<T> and a translation.
//   SE3::Exp / Log   Exp(xi) = [[Exp(phi), Jl(phi) rho], [0, 1]],  Log inverts it (|phi| <= pi).
//   Adj              Exp(Adj xi) = T Exp(xi) T^-1,  Adj = [[R, Hat(t) R], [0, R]].
//   Right/Left Jacobians of SE(3) and their inverses, in closed form with Barfoot's Q block
//   (series near 0).
//
// Scalar type: templates on T; double and ceres::Jet<double, N> both compile (see lie/so3.h).
//
// References
//   [Sola18]    J. Sola, J. Deray, D. Atchuthan, "A micro Lie theory for state estimation in
//               robotics", arXiv:1812.01537.
//   [Barfoot17] T. D. Barfoot, "State Estimation for Robotics", Cambridge University Press, 2017.
#ifndef SPLINECAL_LIE_SE3_H_
#define SPLINECAL_LIE_SE3_H_

#include <Eigen/Core>
#include <cmath>
#include <type_traits>

#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

namespace internal {

// Below this squared angle [rad^2] (angle < 0.1 rad) the coefficients of the SE(3) Jacobians
// use their Taylor series, kept to t^8 (first dropped term O(t^10) <= 1e-10 times a coefficient
// below 1/4e8, i.e. < 1e-18). The threshold is larger than for SO(3) alone because the closed
// forms of c1 and c3 lose about eps / t^2 relative accuracy to cancellation, and Q multiplies
// them by only t or t^3 (not t^2 or t^4): at t = 0.1 the closed forms are still good to ~1e-15.
inline constexpr double kSE3QSmallAngleSq = 1e-2;

// All coefficients of the SE(3) left Jacobian and its inverse, from one sin/cos of t/2
// (t = |phi|). With P = Hat(phi):
//   Jl(phi)    = I + a P + b P^2,     Jl^-1(phi) = I - 1/2 P + c P^2        (lie/so3.h)
//   Q(rho, phi): c1 = b, c2, c3 (see SE3QBlock)
//   a  = (1 - cos t) / t^2          = 1/2  - t^2/24   + t^4/720    - t^6/40320   + t^8/3628800
//   b  = (t - sin t) / t^3          = 1/6  - t^2/120  + t^4/5040   - t^6/362880  + t^8/39916800
//   c  = 1/t^2 - cot(t/2) / (2t)    = 1/12 + t^2/720  + t^4/30240  + t^6/1209600 + t^8/47900160
//   c2 = (t^2 + 2 cos t - 2)/(2t^4) = 1/24 - t^2/720  + t^4/40320  - t^6/3628800 + t^8/479001600
//   c3 = (2t - 3 sin t + t cos t)/(2t^5)
//                                   = 1/120 - t^2/2520 + t^4/120960 - t^6/9979200
//                                     + t^8/1245404160
// Closed forms: a = 2 sin^2(t/2) / t^2 (no cancellation in 1 - cos t); c2 = (1/2 - a) / t^2
// (avoids the cancellation in t^2 + 2 cos t - 2); sin t = 2 sin(t/2) cos(t/2) and
// cos t = 1 - 2 sin^2(t/2).
template <typename T>
struct SE3JacobianCoefficients {
  T a;
  T b;
  T c;
  T c2;
  T c3;
};

template <typename T>
SE3JacobianCoefficients<T> ComputeSE3JacobianCoefficients(const T& theta_sq) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  SE3JacobianCoefficients<T> k;
  if (theta_sq < T(kSE3QSmallAngleSq)) {
    const T t2 = theta_sq;
    const T t4 = t2 * t2;
    const T t6 = t4 * t2;
    const T t8 = t4 * t4;
    k.a = T(0.5) - t2 / T(24.0) + t4 / T(720.0) - t6 / T(40320.0) + t8 / T(3628800.0);
    k.b = T(1.0 / 6.0) - t2 / T(120.0) + t4 / T(5040.0) - t6 / T(362880.0) + t8 / T(39916800.0);
    k.c = T(1.0 / 12.0) + t2 / T(720.0) + t4 / T(30240.0) + t6 / T(1209600.0) + t8 / T(47900160.0);
    k.c2 =
        T(1.0 / 24.0) - t2 / T(720.0) + t4 / T(40320.0) - t6 / T(3628800.0) + t8 / T(479001600.0);
    k.c3 = T(1.0 / 120.0) - t2 / T(2520.0) + t4 / T(120960.0) - t6 / T(9979200.0) +
           t8 / T(1245404160.0);
    return k;
  }
  const T theta = sqrt(theta_sq);
  const T half = T(0.5) * theta;
  const T sin_half = sin(half);
  const T cos_half = cos(half);
  const T sin_t = T(2.0) * sin_half * cos_half;
  const T cos_t = T(1.0) - T(2.0) * sin_half * sin_half;
  k.a = T(2.0) * sin_half * sin_half / theta_sq;
  k.b = (theta - sin_t) / (theta_sq * theta);
  k.c = T(1.0) / theta_sq - cos_half / (T(2.0) * theta * sin_half);
  k.c2 = (T(0.5) - k.a) / theta_sq;
  k.c3 = (T(2.0) * theta - T(3.0) * sin_t + theta * cos_t) / (T(2.0) * theta_sq * theta_sq * theta);
  return k;
}

// Barfoot's Q block of the SE(3) left Jacobian ([Barfoot17], SE(3) left Jacobian), with
// P = Hat(phi), Rh = Hat(rho):
//   Q = 1/2 Rh + c1 (P Rh + Rh P + P Rh P) + c2 (P P Rh + Rh P P - 3 P Rh P)
//              + c3 (P Rh P P + P P Rh P)
// `p` = Hat(phi) and `k` = ComputeSE3JacobianCoefficients(|phi|^2) are passed in (shared with
// the Jl blocks).
template <typename T>
Matrix3<T> SE3QBlock(const Vector3<T>& rho,
                     const Matrix3<T>& p,
                     const SE3JacobianCoefficients<T>& k) {
  const Matrix3<T> r = Hat(rho);
  const Matrix3<T> pr = p * r;
  const Matrix3<T> rp = r * p;
  const Matrix3<T> prp = pr * p;
  const Matrix3<T> ppr = p * pr;
  const Matrix3<T> rpp = rp * p;
  const Matrix3<T> prpp = prp * p;
  const Matrix3<T> pprp = p * prp;
  return T(0.5) * r + k.b * (pr + rp + prp) + k.c2 * (ppr + rpp - T(3.0) * prp) +
         k.c3 * (prpp + pprp);
}

}  // namespace internal

// Hat(xi) = [[Hat(phi), rho], [0, 0]] for xi = [rho; phi] (4x4 twist matrix).
template <
    typename Derived,
    std::enable_if_t<Derived::RowsAtCompileTime == 6 && Derived::ColsAtCompileTime == 1, int> = 0>
Matrix4<typename Derived::Scalar> Hat(const Eigen::MatrixBase<Derived>& xi) {
  using T = typename Derived::Scalar;
  Matrix4<T> m = Matrix4<T>::Zero();
  m.template topLeftCorner<3, 3>() = Hat(xi.template tail<3>());
  m.template topRightCorner<3, 1>() = xi.template head<3>();
  return m;
}

// Vee(Hat(xi)) = xi for a 4x4 twist matrix [[skew, rho], [0, 0]].
template <
    typename Derived,
    std::enable_if_t<Derived::RowsAtCompileTime == 4 && Derived::ColsAtCompileTime == 4, int> = 0>
Vector6<typename Derived::Scalar> Vee(const Eigen::MatrixBase<Derived>& m) {
  using T = typename Derived::Scalar;
  Vector6<T> xi;
  xi << m(0, 3), m(1, 3), m(2, 3), m(2, 1), m(0, 2), m(1, 0);
  return xi;
}

// Aliases with the group in the name (same functions as Hat / Vee above).
template <typename Derived>
Matrix4<typename Derived::Scalar> HatSE3(const Eigen::MatrixBase<Derived>& xi) {
  return Hat(xi);
}
template <typename Derived>
Vector6<typename Derived::Scalar> VeeSE3(const Eigen::MatrixBase<Derived>& m) {
  return Vee(m);
}

// A pose T_a_b = (R_a_b, t_a_b) in SE(3). No invariant beyond SO3's.
template <typename T>
class SE3 {
 public:
  using Scalar = T;
  using Tangent = Vector6<T>;
  static constexpr int kDoF = 6;

  // The identity pose.
  SE3() : t_(Vector3<T>::Zero()) {}
  SE3(const SO3<T>& so3, const Vector3<T>& translation) : so3_(so3), t_(translation) {}

  // From a homogeneous 4x4 matrix [[R, t], [0, 1]] (R orthonormal up to rounding; the rotation
  // is re-normalised as a quaternion). The bottom row is ignored.
  static SE3 FromMatrix(const Matrix4<T>& m) {
    return SE3(SO3<T>::FromMatrix(m.template topLeftCorner<3, 3>()),
               m.template topRightCorner<3, 1>());
  }

  // Exp([rho; phi]) = [[Exp(phi), Jl(phi) rho], [0, 1]]     ([Sola18] SE(3) exp;
  // [Barfoot17] SE(3) exponential). Jl(phi) rho is applied without forming the matrix:
  //   Jl(phi) rho = rho + a phi x rho + b phi x (phi x rho)
  // (a, b from internal::ComputeSO3JacobianCoefficients; series for |phi| < 1e-3 rad).
  static SE3 Exp(const Vector6<T>& xi) {
    const Vector3<T> rho = xi.template head<3>();
    const Vector3<T> phi = xi.template tail<3>();
    const auto k = internal::ComputeSO3JacobianCoefficients(phi.squaredNorm(), false);
    const Vector3<T> phi_x_rho = phi.cross(rho);
    const Vector3<T> t = rho + k.a * phi_x_rho + k.b * phi.cross(phi_x_rho);
    return SE3(SO3<T>::Exp(phi), t);
  }

  // Log(T) = [rho; phi] with phi = Log(R) (|phi| in [0, pi]) and rho = Jl^-1(phi) t:
  //   rho = t - 1/2 phi x t + c phi x (phi x t)      (c: internal::SO3JacobianCoefficients)
  // Exp(Log(T)) = T for every T; Log(Exp(xi)) = xi for |phi| < pi.
  Vector6<T> Log() const {
    const Vector3<T> phi = so3_.Log();
    const auto k = internal::ComputeSO3JacobianCoefficients(phi.squaredNorm(), true);
    const Vector3<T> phi_x_t = phi.cross(t_);
    Vector6<T> xi;
    xi.template head<3>() = t_ - T(0.5) * phi_x_t + k.c * phi.cross(phi_x_t);
    xi.template tail<3>() = phi;
    return xi;
  }

  // T^-1 = (R^T, -R^T t).
  SE3 inverse() const {
    const SO3<T> r_inv = so3_.inverse();
    return SE3(r_inv, -(r_inv * t_));
  }

  // Composition T_a_c = T_a_b * T_b_c = (R_a_b R_b_c, t_a_b + R_a_b t_b_c).
  SE3 operator*(const SE3& other) const { return SE3(so3_ * other.so3_, t_ + so3_ * other.t_); }

  // Transforms a point: p_a = T_a_b * p_b = R_a_b p_b + t_a_b.
  Vector3<T> operator*(const Vector3<T>& p) const { return so3_ * p + t_; }

  const SO3<T>& so3() const { return so3_; }
  const Vector3<T>& translation() const { return t_; }
  Matrix3<T> rotationMatrix() const { return so3_.matrix(); }

  // The 4x4 homogeneous matrix [[R, t], [0, 1]].
  Matrix4<T> matrix() const {
    Matrix4<T> m = Matrix4<T>::Identity();
    m.template topLeftCorner<3, 3>() = so3_.matrix();
    m.template topRightCorner<3, 1>() = t_;
    return m;
  }

  // Adjoint (6x6, acting on [rho; phi]): T Exp(xi) T^-1 = Exp(Adj() xi),
  //   Adj = [[R, Hat(t) R], [0, R]]      ([Sola18] SE(3) adjoint; [Barfoot17] SE(3) adjoint)
  Matrix6<T> Adj() const {
    const Matrix3<T> r = so3_.matrix();
    Matrix6<T> adj;
    adj.template topLeftCorner<3, 3>() = r;
    adj.template topRightCorner<3, 3>() = Hat(t_) * r;
    adj.template bottomLeftCorner<3, 3>().setZero();
    adj.template bottomRightCorner<3, 3>() = r;
    return adj;
  }

  // The same pose with scalar U (static_cast of each coefficient; double -> Jet is fine).
  template <typename U>
  SE3<U> cast() const {
    return SE3<U>(so3_.template cast<U>(), t_.template cast<U>());
  }

 private:
  SO3<T> so3_;
  Vector3<T> t_;
};

// Left Jacobian of SE(3): Exp(xi + d) ~ Exp(Jl(xi) d) Exp(xi).
//   Jl([rho; phi]) = [[Jl(phi), Q(rho, phi)], [0, Jl(phi)]]       ([Barfoot17], SE(3) left
// Jacobian with the Q block; see internal::SE3QBlock for Q and
// internal::ComputeSE3JacobianCoefficients for the coefficients and their series.)
template <typename Derived>
Matrix6<typename Derived::Scalar> LeftJacobianSE3(const Eigen::MatrixBase<Derived>& xi) {
  using T = typename Derived::Scalar;
  const Vector3<T> rho = xi.template head<3>();
  const Vector3<T> phi = xi.template tail<3>();
  const auto k = internal::ComputeSE3JacobianCoefficients(phi.squaredNorm());
  const Matrix3<T> p = Hat(phi);
  const Matrix3<T> jl = Matrix3<T>::Identity() + k.a * p + k.b * (p * p);
  Matrix6<T> j;
  j.template topLeftCorner<3, 3>() = jl;
  j.template topRightCorner<3, 3>() = internal::SE3QBlock(rho, p, k);
  j.template bottomLeftCorner<3, 3>().setZero();
  j.template bottomRightCorner<3, 3>() = jl;
  return j;
}

// Inverse of the SE(3) left Jacobian: Log(Exp(d) Exp(xi)) ~ xi + Jl^-1(xi) d.
//   Jl^-1([rho; phi]) = [[Jl^-1(phi), -Jl^-1(phi) Q(rho, phi) Jl^-1(phi)], [0, Jl^-1(phi)]]
// (block inverse of the upper block-triangular Jl; valid for |phi| < 2 pi).
template <typename Derived>
Matrix6<typename Derived::Scalar> LeftJacobianInverseSE3(const Eigen::MatrixBase<Derived>& xi) {
  using T = typename Derived::Scalar;
  const Vector3<T> rho = xi.template head<3>();
  const Vector3<T> phi = xi.template tail<3>();
  const auto k = internal::ComputeSE3JacobianCoefficients(phi.squaredNorm());
  const Matrix3<T> p = Hat(phi);
  const Matrix3<T> jl_inv = Matrix3<T>::Identity() - T(0.5) * p + k.c * (p * p);
  Matrix6<T> j;
  j.template topLeftCorner<3, 3>() = jl_inv;
  j.template topRightCorner<3, 3>() = -jl_inv * internal::SE3QBlock(rho, p, k) * jl_inv;
  j.template bottomLeftCorner<3, 3>().setZero();
  j.template bottomRightCorner<3, 3>() = jl_inv;
  return j;
}

// Right Jacobian of SE(3): Exp(xi + d) ~ Exp(xi) Exp(Jr(xi) d), i.e.
// Jr(xi) d ~ Log(Exp(xi)^-1 Exp(xi + d)). Jr(xi) = Jl(-xi) ([Sola18], relation between the
// right and left Jacobians), so Jr([rho; phi]) = [[Jr(phi), Q(-rho, -phi)], [0, Jr(phi)]].
template <typename Derived>
Matrix6<typename Derived::Scalar> RightJacobianSE3(const Eigen::MatrixBase<Derived>& xi) {
  using T = typename Derived::Scalar;
  const Vector6<T> minus_xi = -xi;
  return LeftJacobianSE3(minus_xi);
}

// Inverse of the SE(3) right Jacobian: Log(Exp(xi) Exp(d)) ~ xi + Jr^-1(xi) d.
// Jr^-1(xi) = Jl^-1(-xi).
template <typename Derived>
Matrix6<typename Derived::Scalar> RightJacobianInverseSE3(const Eigen::MatrixBase<Derived>& xi) {
  using T = typename Derived::Scalar;
  const Vector6<T> minus_xi = -xi;
  return LeftJacobianInverseSE3(minus_xi);
}

using SE3d = SE3<double>;

}  // namespace splinecal

#endif  // SPLINECAL_LIE_SE3_H_
