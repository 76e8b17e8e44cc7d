// The specific force at a point fixed on a rigid body, from the body's motion at its origin.
//
// A point at r_b (body frame b) has world position p_w + R_w_b r_b; differentiating twice
// (dR/dt = R [w_b]x) gives its acceleration R_w_b (a_b + dw_b x r_b + w_b x (w_b x r_b)), so the
// specific force it senses, rotated into b, is
//
//     f_b(r_b) = f_b + dw_b x r_b + w_b x (w_b x r_b),      f_b = R_w_b^T (a_w - g_w)      (1)
//
// (tangential and centripetal terms; Kalibr's IccImu.addAccelerometerErrorTerms writes the same
// sum). Jacobians of (1), all 3x3:
//     d/d f_b  = I
//     d/d dw_b = -[r_b]x
//     d/d w_b  = (w.r) I + w r^T - 2 r w^T        (d of w (w.r) - r (w.w))
//     d/d r_b  = [dw_b]x + [w_b]x^2
#ifndef SPLINECAL_IMU_RIGID_BODY_POINT_H_
#define SPLINECAL_IMU_RIGID_BODY_POINT_H_

#include <Eigen/Core>

#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// The spline's motion at one instant, in the body (spline) frame b at its origin.
template <typename T>
struct BodyMotion {
  Vector3<T> w_b = Vector3<T>::Zero();   // angular velocity [rad/s]
  Vector3<T> dw_b = Vector3<T>::Zero();  // angular acceleration [rad/s^2]
  Vector3<T> f_b = Vector3<T>::Zero();   // specific force R_w_b^T (a_w - g_w) [m/s^2]
};

// Equation (1): the specific force at r_b, in frame b.
template <typename T>
Vector3<T> SpecificForceAtPoint(const BodyMotion<T>& motion, const Vector3<T>& r_b) {
  return motion.f_b + motion.dw_b.cross(r_b) + motion.w_b.cross(motion.w_b.cross(r_b));
}

// d (w x (w x r)) / d w.
inline Eigen::Matrix3d CentripetalJacobian(const Eigen::Vector3d& w, const Eigen::Vector3d& r) {
  return w.dot(r) * Eigen::Matrix3d::Identity() + w * r.transpose() - 2.0 * r * w.transpose();
}

// d (dw x r + w x (w x r)) / d r = [dw]x + [w]x^2.
inline Eigen::Matrix3d LeverArmJacobian(const Eigen::Vector3d& w, const Eigen::Vector3d& dw) {
  const Eigen::Matrix3d w_x = Hat(w);
  return Hat(dw) + w_x * w_x;
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_RIGID_BODY_POINT_H_
