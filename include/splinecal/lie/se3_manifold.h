// Ceres manifolds for a pose block and a rotation block, with splinecal's RIGHT perturbation.
//
// Parameter block layouts (agreed for the whole library)
//   pose:      double pose[7]     = {px, py, pz, qx, qy, qz, qw}
//              translation t_a_b first, then the unit Hamilton quaternion of R_a_b in Eigen's
//              memory order (Eigen::Quaterniond::coeffs()).
//   rotation:  double rotation[4] = {qx, qy, qz, qw}
//
// Retraction (lie/se3.h, "ONE perturbation convention"):
//   Plus(x, d)  = x * Exp(d),          d = [rho; phi] (pose) or phi (rotation)
//   Minus(y, x) = Log(x^-1 * y)        (shortest rotation: angle in [0, pi])
// so a Jacobian written as d f(T Exp(d)) / d d at d = 0 is exactly what Ceres needs after
// PlusJacobian. Do NOT mix with ceres::QuaternionManifold / EigenQuaternionManifold: they
// perturb on the LEFT (Exp(d) * q), and Jacobians written for one are wrong for the other.
//
// Jacobians at d = 0 (q = (w, v) the quaternion of x, R its rotation matrix):
//   Plus:  d t' / d rho = R,  d t' / d phi = 0,
//          d v' / d phi = 1/2 (w I + [v]x),  d w' / d phi = -1/2 v^T     (q (x) [1, phi/2])
//   Minus: d rho / d t_y = R^T,  d rho / d q_y = 0,
//          d phi / d v_y = 2 (w I - [v]x),  d phi / d w_y = -2 v       (2 vec(q^* (x) q_y))
// MinusJacobian * PlusJacobian = I (because |q| = 1).
//
// Plus renormalises the quaternion it writes; Minus and PoseFromBlock normalise the
// quaternions they read. The radial direction of a quaternion therefore never matters, which
// keeps Ceres' numeric checks (which perturb the ambient block off the unit sphere) and long
// optimisations (rounding drift) consistent with the analytic Jacobians.
//
// Plus(x, Minus(y, x)) equals y up to the sign of the quaternion: Minus returns the shortest
// rotation, so the result is the representative of y in the hemisphere of x's quaternion.
#ifndef SPLINECAL_LIE_SE3_MANIFOLD_H_
#define SPLINECAL_LIE_SE3_MANIFOLD_H_

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <Eigen/Geometry>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// Sizes of the parameter blocks.
inline constexpr int kPoseBlockSize = 7;
inline constexpr int kRotationBlockSize = 4;

// Reads a rotation block {qx, qy, qz, qw}; the quaternion is normalised (it must be nonzero).
// Works with T = double and T = ceres::Jet (normalising only removes the radial derivative
// component, which the manifold's PlusJacobian never uses).
template <typename T>
SO3<T> RotationFromBlock(const T* block) {
  return SO3<T>::FromQuaternion(Eigen::Quaternion<T>(block[3], block[0], block[1], block[2]));
}

// Writes a rotation into a block {qx, qy, qz, qw}.
template <typename T>
void RotationToBlock(const SO3<T>& rotation, T* block) {
  const Eigen::Quaternion<T>& q = rotation.quaternion();
  block[0] = q.x();
  block[1] = q.y();
  block[2] = q.z();
  block[3] = q.w();
}

// Reads a pose block {px, py, pz, qx, qy, qz, qw} into T_a_b; the quaternion is normalised.
template <typename T>
SE3<T> PoseFromBlock(const T* block) {
  return SE3<T>(RotationFromBlock(block + 3), Vector3<T>(block[0], block[1], block[2]));
}

// Writes T_a_b into a pose block {px, py, pz, qx, qy, qz, qw}.
template <typename T>
void PoseToBlock(const SE3<T>& pose, T* block) {
  block[0] = pose.translation()(0);
  block[1] = pose.translation()(1);
  block[2] = pose.translation()(2);
  RotationToBlock(pose.so3(), block + 3);
}

namespace internal {

// d (q (x) Exp(phi)) / d phi at phi = 0 for a quaternion block {qx, qy, qz, qw}: 4x3, rows in
// block order.
inline Eigen::Matrix<double, 4, 3> QuaternionRightPlusJacobian(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 4, 3> j;
  j.topRows<3>() = 0.5 * (q.w() * Eigen::Matrix3d::Identity() + Hat(q.vec()));
  j.bottomRows<1>() = -0.5 * q.vec().transpose();
  return j;
}

// d Log(q^* (x) q_y) / d q_y at q_y = q: 3x4, columns in block order {qx, qy, qz, qw}.
inline Eigen::Matrix<double, 3, 4> QuaternionRightMinusJacobian(const Eigen::Quaterniond& q) {
  Eigen::Matrix<double, 3, 4> j;
  j.leftCols<3>() = 2.0 * (q.w() * Eigen::Matrix3d::Identity() - Hat(q.vec()));
  j.rightCols<1>() = -2.0 * q.vec();
  return j;
}

}  // namespace internal

// The pose manifold: ambient 7 ({px, py, pz, qx, qy, qz, qw}), tangent 6 ([rho; phi]).
class SE3Manifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kPoseBlockSize; }
  int TangentSize() const override { return 6; }

  // x_plus_delta = PoseToBlock(PoseFromBlock(x) * SE3d::Exp(delta)).
  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const SE3d pose = PoseFromBlock(x) * SE3d::Exp(Eigen::Map<const Vector6d>(delta));
    PoseToBlock(SE3d(SO3d::FromQuaternion(pose.so3().quaternion()), pose.translation()),
                x_plus_delta);
    return true;
  }

  // jacobian: 7x6 row-major, d Plus(x, delta) / d delta at delta = 0 (see the file comment).
  bool PlusJacobian(const double* x, double* jacobian) const override {
    const SE3d pose = PoseFromBlock(x);
    Eigen::Map<Eigen::Matrix<double, 7, 6, Eigen::RowMajor>> j(jacobian);
    j.setZero();
    j.topLeftCorner<3, 3>() = pose.so3().matrix();
    j.bottomRightCorner<4, 3>() = internal::QuaternionRightPlusJacobian(pose.so3().quaternion());
    return true;
  }

  // tangent_matrix (num_rows x 6) = ambient_matrix (num_rows x 7) * PlusJacobian(x), row-major,
  // without forming the zero blocks.
  bool RightMultiplyByPlusJacobian(const double* x,
                                   const int num_rows,
                                   const double* ambient_matrix,
                                   double* tangent_matrix) const override {
    if (num_rows == 0) return true;
    const SE3d pose = PoseFromBlock(x);
    Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>> a(
        ambient_matrix, num_rows, 7);
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 6, Eigen::RowMajor>> t(
        tangent_matrix, num_rows, 6);
    t.leftCols<3>() = a.leftCols<3>() * pose.so3().matrix();
    t.rightCols<3>() =
        a.rightCols<4>() * internal::QuaternionRightPlusJacobian(pose.so3().quaternion());
    return true;
  }

  // y_minus_x = Log(PoseFromBlock(x)^-1 * PoseFromBlock(y)).
  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<Vector6d> out(y_minus_x);
    out = (PoseFromBlock(x).inverse() * PoseFromBlock(y)).Log();
    return true;
  }

  // jacobian: 6x7 row-major, d Minus(y, x) / d y at y = x (see the file comment).
  bool MinusJacobian(const double* x, double* jacobian) const override {
    const SE3d pose = PoseFromBlock(x);
    Eigen::Map<Eigen::Matrix<double, 6, 7, Eigen::RowMajor>> j(jacobian);
    j.setZero();
    j.topLeftCorner<3, 3>() = pose.so3().matrix().transpose();
    j.bottomRightCorner<3, 4>() = internal::QuaternionRightMinusJacobian(pose.so3().quaternion());
    return true;
  }
};

// The rotation manifold: ambient 4 ({qx, qy, qz, qw}), tangent 3 (phi). Plus(x, d) = x Exp(d),
// Minus(y, x) = Log(x^-1 y), same conventions as SE3Manifold.
class SO3Manifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return kRotationBlockSize; }
  int TangentSize() const override { return 3; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const SO3d r = RotationFromBlock(x) * SO3d::Exp(Eigen::Map<const Eigen::Vector3d>(delta));
    RotationToBlock(SO3d::FromQuaternion(r.quaternion()), x_plus_delta);
    return true;
  }

  // jacobian: 4x3 row-major.
  bool PlusJacobian(const double* x, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 4, 3, Eigen::RowMajor>> j(jacobian);
    j = internal::QuaternionRightPlusJacobian(RotationFromBlock(x).quaternion());
    return true;
  }

  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    Eigen::Map<Eigen::Vector3d> out(y_minus_x);
    out = (RotationFromBlock(x).inverse() * RotationFromBlock(y)).Log();
    return true;
  }

  // jacobian: 3x4 row-major.
  bool MinusJacobian(const double* x, double* jacobian) const override {
    Eigen::Map<Eigen::Matrix<double, 3, 4, Eigen::RowMajor>> j(jacobian);
    j = internal::QuaternionRightMinusJacobian(RotationFromBlock(x).quaternion());
    return true;
  }
};

}  // namespace splinecal

#endif  // SPLINECAL_LIE_SE3_MANIFOLD_H_
