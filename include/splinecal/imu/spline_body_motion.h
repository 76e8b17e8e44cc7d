// The spline's body motion at one instant (imu/rigid_body_point.h's BodyMotion): what the IMU
// models (imu/imu_intrinsic_model.h) take from the trajectory.
#ifndef SPLINECAL_IMU_SPLINE_BODY_MOTION_H_
#define SPLINECAL_IMU_SPLINE_BODY_MOTION_H_

#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/types.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {

// w_b, dw_b and f_b = R_w_b^T (a_w - g_w) of `spline` at `segment` (g_w from GravityWorld).
template <typename T>
BodyMotion<T> SplineBodyMotion(const SE3Spline<T>& spline,
                               const Segment<T>& segment,
                               const Vector3<T>& g_w) {
  BodyMotion<T> motion;
  SE3<T> T_w_b;
  Vector3<T> a_w;
  spline.Evaluate(segment, &T_w_b, &motion.w_b, &motion.dw_b, nullptr, &a_w);
  motion.f_b = T_w_b.rotationMatrix().transpose() * (a_w - g_w);
  return motion;
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_SPLINE_BODY_MOTION_H_
