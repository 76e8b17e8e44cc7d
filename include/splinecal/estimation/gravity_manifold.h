// The gravity vector g_w as a Ceres parameter block with 2 degrees of freedom: its direction moves
// on the sphere |g_w| = g, its magnitude stays what it was initialised to (--gravity,
// docs/conventions.md "IMU model").
//
// Block layout: double gravity[3] = g_w (ambient 3, tangent 2). Built on estimation/gravity_tangent.h
// (a tangent basis B(g) that is well conditioned for EVERY direction of g, [seed001]):
//
//   Plus(x, w)   = RetractGravity(x, w)   = |x| (cos|w| d + sin|w|/|w| B w),  d = x / |x|
//                  (the great circle through x in the direction B w, for the angle |w| [rad])
//   Minus(y, x)  = theta / sin(theta) B^T d_y,   d_y = y / |y|,   theta = angle(x, y)
//                  (the w with Plus(x, w) = y for |y| = |x| and theta < pi: the component of
//                  d_y orthogonal to d has norm sin(theta) and direction B w / |w|)
//   PlusJacobian(x)  = |x| B          (3x2)
//   MinusJacobian(x) = B^T / |x|      (2x3; d d_y / d y = (I - d d^T) / |x| at y = x, B^T d = 0)
//
// MinusJacobian * PlusJacobian = B^T B = I. The tangent coordinates w are angles [rad], so the
// covariance of a gravity block in tangent space is the covariance of its direction in rad^2.
//
// Minus(y, x) with y off the sphere of x uses only y's direction. theta / sin(theta) uses the
// series 1 + theta^2/6 + 7 theta^4/360 below theta = 1e-4 rad (first dropped term
// 31 theta^6 / 15120 ~ 2e-27).
#ifndef SPLINECAL_ESTIMATION_GRAVITY_MANIFOLD_H_
#define SPLINECAL_ESTIMATION_GRAVITY_MANIFOLD_H_

#include <ceres/manifold.h>

#include <Eigen/Core>
#include <cmath>

#include "splinecal/estimation/gravity_tangent.h"

namespace splinecal {

inline constexpr int kGravityBlockSize = 3;

class GravityManifold : public ceres::Manifold {
 public:
  int AmbientSize() const override { return 3; }
  int TangentSize() const override { return 2; }

  bool Plus(const double* x, const double* delta, double* x_plus_delta) const override {
    const Eigen::Map<const Eigen::Vector3d> g(x);
    if (!(g.norm() > 0.0) || !std::isfinite(g.norm())) return false;
    Eigen::Map<Eigen::Vector3d> out(x_plus_delta);
    out = RetractGravity(g, Eigen::Map<const Eigen::Vector2d>(delta));
    return true;
  }

  // jacobian: 3x2 row-major.
  bool PlusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Eigen::Vector3d> g(x);
    const double norm = g.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return false;
    Eigen::Map<Eigen::Matrix<double, 3, 2, Eigen::RowMajor>> J(jacobian);
    J = norm * GravityTangentBasis(g);
    return true;
  }

  bool Minus(const double* y, const double* x, double* y_minus_x) const override {
    const Eigen::Map<const Eigen::Vector3d> g_x(x);
    const Eigen::Map<const Eigen::Vector3d> g_y(y);
    const double norm_x = g_x.norm();
    const double norm_y = g_y.norm();
    if (!(norm_x > 0.0) || !(norm_y > 0.0) || !std::isfinite(norm_x) || !std::isfinite(norm_y)) {
      return false;
    }
    const Eigen::Vector3d d_x = g_x / norm_x;
    const Eigen::Vector3d d_y = g_y / norm_y;
    const double sin_theta = d_x.cross(d_y).norm();
    const double cos_theta = d_x.dot(d_y);
    const double theta = std::atan2(sin_theta, cos_theta);
    double ratio;  // theta / sin(theta)
    if (theta < kSmallAngle) {
      const double theta_sq = theta * theta;
      ratio = 1.0 + theta_sq / 6.0 + 7.0 * theta_sq * theta_sq / 360.0;
    } else {
      ratio = theta / sin_theta;
    }
    Eigen::Map<Eigen::Vector2d> out(y_minus_x);
    out = ratio * GravityTangentBasis(g_x).transpose() * d_y;
    return true;
  }

  // jacobian: 2x3 row-major.
  bool MinusJacobian(const double* x, double* jacobian) const override {
    const Eigen::Map<const Eigen::Vector3d> g(x);
    const double norm = g.norm();
    if (!(norm > 0.0) || !std::isfinite(norm)) return false;
    Eigen::Map<Eigen::Matrix<double, 2, 3, Eigen::RowMajor>> J(jacobian);
    J = GravityTangentBasis(g).transpose() / norm;
    return true;
  }

 private:
  // Below this angle [rad] theta / sin(theta) uses its series (file comment).
  static constexpr double kSmallAngle = 1e-4;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_GRAVITY_MANIFOLD_H_
