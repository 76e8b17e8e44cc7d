// Predicted gyro and accelerometer readings of one IMU under each of Kalibr's models
// (imu/imu_model_kind.h), from the spline's body motion at the reading's time:
//
//   calibrated                      accel = C_i_b f_b(r_b) + b_a,     gyro = C_i_b w_b + b_g
//   scale-misalignment              imu/scale_misalignment_model.h, equations (1), (2)
//   scale-misalignment-size-effect  accel: imu/size_effect_model.h; gyro: as scale-misalignment
//
// A model reads only its own parameters: `calibrated` ignores M_a, M_g, A, C_gyro_i, ry_i, rz_i
// (their Jacobian blocks are zero), `scale-misalignment` ignores ry_i, rz_i.
#ifndef SPLINECAL_IMU_IMU_INTRINSIC_MODEL_H_
#define SPLINECAL_IMU_IMU_INTRINSIC_MODEL_H_

#include <Eigen/Core>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/imu/scale_misalignment_model.h"
#include "splinecal/imu/size_effect_model.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// The parameters `kind` reads; the others at their nominal values.
template <typename T>
ImuIntrinsics<T> ModelIntrinsics(ImuModelKind kind, const ImuIntrinsics<T>& p) {
  ImuIntrinsics<T> out;
  out.C_i_b = p.C_i_b;
  out.r_b = p.r_b;
  if (kind == ImuModelKind::kCalibrated) return out;
  out.M_a = p.M_a;
  out.M_g = p.M_g;
  out.A = p.A;
  out.C_gyro_i = p.C_gyro_i;
  if (kind == ImuModelKind::kScaleMisalignment) return out;
  out.ry_i = p.ry_i;
  out.rz_i = p.rz_i;
  return out;
}

// Either output may be nullptr. Templated (double or ceres::Jet).
template <typename T>
void PredictImuReadings(ImuModelKind kind,
                        const ImuIntrinsics<T>& p,
                        const BodyMotion<T>& motion,
                        const Vector3<T>& b_g,
                        const Vector3<T>& b_a,
                        Vector3<T>* gyro,
                        Vector3<T>* accel) {
  const ImuIntrinsics<T> q = ModelIntrinsics(kind, p);
  if (gyro != nullptr) *gyro = PredictScaleMisalignmentGyro(q, motion, b_g);
  if (accel == nullptr) return;
  *accel = kind == ImuModelKind::kScaleMisalignmentSizeEffect
               ? PredictSizeEffectAccel(q, motion, b_a)
               : PredictScaleMisalignmentAccel(q, motion, b_a);
}

// The same with the analytic Jacobians (any pointer may be nullptr).
inline void PredictImuReadings(ImuModelKind kind,
                               const ImuIntrinsicsd& p,
                               const BodyMotion<double>& motion,
                               const Eigen::Vector3d& b_g,
                               const Eigen::Vector3d& b_a,
                               Eigen::Vector3d* gyro,
                               Eigen::Vector3d* accel,
                               ImuGyroJacobians* J_gyro,
                               ImuAccelJacobians* J_accel) {
  const ImuIntrinsicsd q = ModelIntrinsics(kind, p);
  if (gyro != nullptr || J_gyro != nullptr) {
    const Eigen::Vector3d g = PredictScaleMisalignmentGyro(q, motion, b_g, J_gyro);
    if (gyro != nullptr) *gyro = g;
    if (J_gyro != nullptr && kind == ImuModelKind::kCalibrated) {
      J_gyro->M_g.setZero();
      J_gyro->A.setZero();
      J_gyro->phi_gyro_i.setZero();
    }
  }
  if (accel == nullptr && J_accel == nullptr) return;
  const Eigen::Vector3d a = kind == ImuModelKind::kScaleMisalignmentSizeEffect
                                ? PredictSizeEffectAccel(q, motion, b_a, J_accel)
                                : PredictScaleMisalignmentAccel(q, motion, b_a, J_accel);
  if (accel != nullptr) *accel = a;
  if (J_accel != nullptr && kind == ImuModelKind::kCalibrated) J_accel->M_a.setZero();
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_INTRINSIC_MODEL_H_
