// SO(3), the group of 3D rotations, stored as a unit Hamilton quaternion.
//
// What this header implements
//   SO3<T>            a rotation R, held as a unit quaternion q = (w, x, y, z), q and -q being the
//                     same rotation (docs/conventions.md, "Frames and notation").
//   Hat / Vee         so(3) <-> R^3:  Hat(v) = [v]x, the skew matrix with [v]x p = v x p.
//   SO3::Exp / Log    the exponential and logarithm maps (rotation vector phi = angle * axis).
//   Right/Left Jacobians and their inverses (closed forms, Taylor series near 0).
//
// Perturbation convention (the one of the whole library, see lie/se3.h): RIGHT.
//   R (+) d = R * Exp(d).  Every Jacobian with respect to a rotation in splinecal is
//   d f(R Exp(d)) / d d at d = 0.
//
// Scalar type: every function is a template on T and compiles with double and with
// ceres::Jet<double, N>. Math functions are called unqualified after `using std::sin;` etc. so
// that argument-dependent lookup picks ceres::sin for Jets. Near-zero branches use polynomial
// series: they are exact to double precision there AND keep Jet derivatives finite where the
// closed forms would divide 0 by 0 (sqrt'(0) is infinite).
//
// References (full entries in docs/references.md)
//   [Sola18]    J. Sola, J. Deray, D. Atchuthan, "A micro Lie theory for state estimation in
//               robotics", arXiv:1812.01537.
//   [Barfoot17] T. D. Barfoot, "State Estimation for Robotics", Cambridge University Press, 2017.
#ifndef SPLINECAL_LIE_SO3_H_
#define SPLINECAL_LIE_SO3_H_

#include <glog/logging.h>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cmath>
#include <type_traits>

#include "splinecal/lie/types.h"

namespace splinecal {

namespace internal {

// Below this squared angle [rad^2] (angle < 1e-3 rad) the SO(3) functions switch to their Taylor
// series, kept to theta^4. The first dropped term is O(theta^6) <= 1e-18 times a coefficient
// below 1/46080, far under double precision (relative 1.1e-16).
inline constexpr double kSO3SmallAngleSq = 1e-6;

// Coefficients of the SO(3) Jacobians, as functions of the squared angle theta^2 = |phi|^2:
//   Jl(phi)    = I + a [phi]x + b [phi]x^2      Jr(phi)    = I - a [phi]x + b [phi]x^2
//   Jl^-1(phi) = I - 1/2 [phi]x + c [phi]x^2    Jr^-1(phi) = I + 1/2 [phi]x + c [phi]x^2
// with
//   a = (1 - cos t) / t^2    = 2 sin^2(t/2) / t^2    = 1/2  - t^2/24  + t^4/720   - O(t^6)
//   b = (t - sin t) / t^3                            = 1/6  - t^2/120 + t^4/5040  - O(t^6)
//   c = 1/t^2 - cot(t/2) / (2 t)                     = 1/12 + t^2/720 + t^4/30240 + O(t^6)
// ([Sola18] SO(3) Jacobians; [Barfoot17] SO(3) left Jacobian and its inverse.)
// a uses the sin^2 form (no cancellation in 1 - cos t). c is written with cot(t/2) =
// cos(t/2) / sin(t/2), finite up to t = pi and beyond (the inverse Jacobians are singular only
// at t = 2 pi k, k != 0).
template <typename T>
struct SO3JacobianCoefficients {
  T a;
  T b;
  T c;
};

// Computes a and b, and c when `with_c` (c costs a division and a cos more).
template <typename T>
SO3JacobianCoefficients<T> ComputeSO3JacobianCoefficients(const T& theta_sq, bool with_c) {
  using std::cos;
  using std::sin;
  using std::sqrt;
  SO3JacobianCoefficients<T> k;
  if (theta_sq < T(kSO3SmallAngleSq)) {
    const T theta_4 = theta_sq * theta_sq;
    k.a = T(0.5) - theta_sq / T(24.0) + theta_4 / T(720.0);
    k.b = T(1.0 / 6.0) - theta_sq / T(120.0) + theta_4 / T(5040.0);
    k.c = T(1.0 / 12.0) + theta_sq / T(720.0) + theta_4 / T(30240.0);
    return k;
  }
  const T theta = sqrt(theta_sq);
  const T half = T(0.5) * theta;
  const T sin_half = sin(half);
  k.a = T(2.0) * sin_half * sin_half / theta_sq;
  k.b = (theta - sin(theta)) / (theta_sq * theta);
  k.c = with_c ? T(1.0) / theta_sq - cos(half) / (T(2.0) * theta * sin_half) : T(0.0);
  return k;
}

}  // namespace internal

// Hat(v) = [v]x = [[0, -v3, v2], [v3, 0, -v1], [-v2, v1, 0]], so that Hat(v) p = v x p.
// Accepts any 3-vector expression.
template <
    typename Derived,
    std::enable_if_t<Derived::RowsAtCompileTime == 3 && Derived::ColsAtCompileTime == 1, int> = 0>
Matrix3<typename Derived::Scalar> Hat(const Eigen::MatrixBase<Derived>& v) {
  using T = typename Derived::Scalar;
  Matrix3<T> m;
  // clang-format off
  m << T(0.0), -v(2),   v(1),
       v(2),    T(0.0), -v(0),
       -v(1),   v(0),   T(0.0);
  // clang-format on
  return m;
}

// Vee(Hat(v)) = v. Reads the three entries below the diagonal; m must be skew-symmetric.
template <
    typename Derived,
    std::enable_if_t<Derived::RowsAtCompileTime == 3 && Derived::ColsAtCompileTime == 3, int> = 0>
Vector3<typename Derived::Scalar> Vee(const Eigen::MatrixBase<Derived>& m) {
  return Vector3<typename Derived::Scalar>(m(2, 1), m(0, 2), m(1, 0));
}

// A rotation R in SO(3), held as a unit Hamilton quaternion q (Eigen::Quaternion, so q.coeffs()
// is [x, y, z, w] in memory). Invariant: |q| = 1 up to rounding; the constructor does not
// normalise (FromQuaternion does). Composition does not renormalise either: after thousands of
// products, call FromQuaternion(R.quaternion()) to remove the drift.
template <typename T>
class SO3 {
 public:
  using Scalar = T;
  using Tangent = Vector3<T>;
  static constexpr int kDoF = 3;

  // The identity rotation.
  SO3() : q_(T(1.0), T(0.0), T(0.0), T(0.0)) {}

  // Wraps q, which must be a unit quaternion (DCHECKed for floating-point T).
  explicit SO3(const Eigen::Quaternion<T>& q) : q_(q) {
    if constexpr (std::is_floating_point_v<T>) {
      DCHECK_LT(std::abs(q.squaredNorm() - T(1.0)), T(1e-6)) << "SO3 needs a unit quaternion";
    }
  }

  // Normalises q first (for quaternions read from files or built by hand). q must be nonzero.
  static SO3 FromQuaternion(const Eigen::Quaternion<T>& q) { return SO3(q.normalized()); }

  // From a rotation matrix (orthonormal up to rounding, det +1); the quaternion is normalised.
  static SO3 FromMatrix(const Matrix3<T>& m) {
    Eigen::Quaternion<T> q(m);
    return SO3(q.normalized());
  }

  // Exp(phi): the rotation by the angle t = |phi| [rad] about the axis phi / t. As a quaternion
  //   q = [cos(t/2), sin(t/2)/t * phi]                             ([Sola18] SO(3) exp, quaternion)
  // For t^2 < 1e-6 the series (kept to t^4, first dropped term O(t^6)):
  //   cos(t/2)   = 1   - t^2/8  + t^4/384
  //   sin(t/2)/t = 1/2 - t^2/48 + t^4/3840
  // Any phi is accepted (|phi| > pi wraps around).
  static SO3 Exp(const Vector3<T>& phi) {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta_sq = phi.squaredNorm();
    T w;
    T k;  // sin(t/2) / t
    if (theta_sq < T(internal::kSO3SmallAngleSq)) {
      const T theta_4 = theta_sq * theta_sq;
      w = T(1.0) - theta_sq / T(8.0) + theta_4 / T(384.0);
      k = T(0.5) - theta_sq / T(48.0) + theta_4 / T(3840.0);
    } else {
      const T theta = sqrt(theta_sq);
      const T half = T(0.5) * theta;
      w = cos(half);
      k = sin(half) / theta;
    }
    return SO3(Eigen::Quaternion<T>(w, k * phi(0), k * phi(1), k * phi(2)));
  }

  // Log(R): the rotation vector phi with angle |phi| in [0, pi], Exp(Log(R)) = R.
  // q and -q are folded onto the hemisphere w >= 0, then with n = |(x, y, z)|:
  //   t = 2 atan2(n, w) in [0, pi],   phi = t / n * (x, y, z)
  // atan2 stays accurate near t = pi (w -> 0), where acos(w) or asin(n) would lose half the
  // digits. For a rotation by exactly pi both phi and -phi are valid; the sign of the
  // quaternion's vector part decides. Near zero, with x = n / w (x^2 < 1e-6, t < 2e-3 rad):
  //   phi = 2 atan(x)/x * (x, y, z) / w,   atan(x)/x = 1 - x^2/3 + x^4/5   (first dropped: x^6/7)
  // Both branches are invariant to the scale of q.
  Vector3<T> Log() const {
    using std::atan2;
    using std::sqrt;
    T w = q_.w();
    Vector3<T> v = q_.vec();
    if (w < T(0.0)) {  // Fold q and -q.
      w = -w;
      v = -v;
    }
    const T n_sq = v.squaredNorm();
    const T w_sq = w * w;
    if (n_sq < T(internal::kSO3SmallAngleSq) * w_sq) {
      const T x_sq = n_sq / w_sq;
      const T atan_ratio = T(1.0) - x_sq / T(3.0) + x_sq * x_sq / T(5.0);
      return (T(2.0) * atan_ratio / w) * v;
    }
    const T n = sqrt(n_sq);
    return (T(2.0) * atan2(n, w) / n) * v;
  }

  SO3 inverse() const { return SO3(q_.conjugate()); }

  // Composition R_a_c = R_a_b * R_b_c (Hamilton product of the quaternions).
  SO3 operator*(const SO3& other) const { return SO3(q_ * other.q_); }

  // Rotates a point: p_a = R_a_b * p_b. With q = (w, u):  p + 2w (u x p) + 2 u x (u x p).
  Vector3<T> operator*(const Vector3<T>& p) const {
    const Vector3<T> u = q_.vec();
    const Vector3<T> t = T(2.0) * u.cross(p);
    return p + q_.w() * t + u.cross(t);
  }

  Matrix3<T> matrix() const { return q_.toRotationMatrix(); }
  const Eigen::Quaternion<T>& quaternion() const { return q_; }

  // Adjoint: Exp(Adj() phi) = R Exp(phi) R^-1, i.e. Hat(Adj phi) = R Hat(phi) R^T. For SO(3)
  // Adj = R.
  Matrix3<T> Adj() const { return matrix(); }

  // The same rotation with scalar U (double -> Jet, or Jet's value type, via static_cast of each
  // coefficient; a Jet -> double cast is not defined and does not compile).
  template <typename U>
  SO3<U> cast() const {
    return SO3<U>(q_.template cast<U>());
  }

 private:
  Eigen::Quaternion<T> q_;
};

// Right Jacobian of SO(3): Exp(phi + d) ~ Exp(phi) Exp(Jr(phi) d) for small d. Equivalently
// Jr(phi) d ~ Log(Exp(phi)^-1 Exp(phi + d)).
//   Jr(phi) = I - (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2,  t = |phi|
// ([Sola18] SO(3) right Jacobian; series near 0 in internal::SO3JacobianCoefficients.)
// Jr(phi) = Jl(-phi) = Jl(phi)^T.
template <typename Derived>
Matrix3<typename Derived::Scalar> RightJacobianSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const Vector3<T> phi_v = phi;
  const auto k = internal::ComputeSO3JacobianCoefficients(phi_v.squaredNorm(), false);
  const Matrix3<T> phi_x = Hat(phi_v);
  return Matrix3<T>::Identity() - k.a * phi_x + k.b * (phi_x * phi_x);
}

// Inverse of Jr: Log(Exp(phi) Exp(d)) ~ phi + Jr^-1(phi) d.
//   Jr^-1(phi) = I + 1/2 [phi]x + (1/t^2 - cot(t/2)/(2t)) [phi]x^2     (valid for t < 2 pi)
template <typename Derived>
Matrix3<typename Derived::Scalar> RightJacobianInverseSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const Vector3<T> phi_v = phi;
  const auto k = internal::ComputeSO3JacobianCoefficients(phi_v.squaredNorm(), true);
  const Matrix3<T> phi_x = Hat(phi_v);
  return Matrix3<T>::Identity() + T(0.5) * phi_x + k.c * (phi_x * phi_x);
}

// Left Jacobian of SO(3): Exp(phi + d) ~ Exp(Jl(phi) d) Exp(phi).
//   Jl(phi) = I + (1 - cos t)/t^2 [phi]x + (t - sin t)/t^3 [phi]x^2 = Jr(phi)^T = Jr(-phi)
// ([Sola18] SO(3) left Jacobian; [Barfoot17] SO(3) left Jacobian, "J".)
template <typename Derived>
Matrix3<typename Derived::Scalar> LeftJacobianSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const Vector3<T> phi_v = phi;
  const auto k = internal::ComputeSO3JacobianCoefficients(phi_v.squaredNorm(), false);
  const Matrix3<T> phi_x = Hat(phi_v);
  return Matrix3<T>::Identity() + k.a * phi_x + k.b * (phi_x * phi_x);
}

// Inverse of Jl: Log(Exp(d) Exp(phi)) ~ phi + Jl^-1(phi) d.
//   Jl^-1(phi) = I - 1/2 [phi]x + (1/t^2 - cot(t/2)/(2t)) [phi]x^2     (valid for t < 2 pi)
template <typename Derived>
Matrix3<typename Derived::Scalar> LeftJacobianInverseSO3(const Eigen::MatrixBase<Derived>& phi) {
  using T = typename Derived::Scalar;
  const Vector3<T> phi_v = phi;
  const auto k = internal::ComputeSO3JacobianCoefficients(phi_v.squaredNorm(), true);
  const Matrix3<T> phi_x = Hat(phi_v);
  return Matrix3<T>::Identity() - T(0.5) * phi_x + k.c * (phi_x * phi_x);
}

using SO3d = SO3<double>;

}  // namespace splinecal

#endif  // SPLINECAL_LIE_SO3_H_
