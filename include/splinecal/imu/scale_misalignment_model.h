// Kalibr's `scale-misalignment` IMU model (IccScaledMisalignedImu in IccSensors.py; Rehder et
// al., "Extending kalibr", ICRA 2016), on the spline's body motion (imu/rigid_body_point.h):
//
//     f      = f_b + dw_b x r_b + w_b x (w_b x r_b)           specific force at the IMU, in b
//     accel  = M_a C_i_b f + b_a                                                          (1)
//     gyro   = M_g C_gyro_b w_b + A C_gyro_b f + b_g,   C_gyro_b = C_gyro_i C_i_b          (2)
//
// A multiplies the true specific force at the IMU rotated into the gyro frame, not the
// accelerometer's reading. With M_a = M_g = I, A = 0, C_gyro_i = I this is the `calibrated`
// model (IccImu), and with C_i_b = I, r_b = 0 too it is imu/imu_model.h's PredictImu.
//
// Jacobians (right perturbation C -> C Exp(phi), so d(C v)/dphi = -C [v]x; D(w, r) =
// d(w x (w x r))/dw and L(w, dw) = [dw]x + [w]x^2 from imu/rigid_body_point.h):
//     accel:  d/dw_b = M_a C_i_b D(w_b, r_b)      d/ddw_b = -M_a C_i_b [r_b]x
//             d/df_b = M_a C_i_b                  d/dr_b  = M_a C_i_b L(w_b, dw_b)
//             d/dphi_i_b = -M_a C_i_b [f]x        d/dM_a  = LowerTriangularProductJacobian(C_i_b f)
//     gyro:   d/dw_b = M_g C_gyro_b + A C_gyro_b D(w_b, r_b)
//             d/ddw_b = -A C_gyro_b [r_b]x        d/df_b = A C_gyro_b
//             d/dr_b  = A C_gyro_b L(w_b, dw_b)
//             d/dphi_i_b    = -(M_g C_gyro_b [w_b]x + A C_gyro_b [f]x)
//             d/dphi_gyro_i = -(M_g C_gyro_i [C_i_b w_b]x + A C_gyro_i [C_i_b f]x)
//             d/dM_g = LowerTriangularProductJacobian(C_gyro_b w_b)
//             d/dA   = FullMatrixProductJacobian(C_gyro_b f)
#ifndef SPLINECAL_IMU_SCALE_MISALIGNMENT_MODEL_H_
#define SPLINECAL_IMU_SCALE_MISALIGNMENT_MODEL_H_

#include <Eigen/Core>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// Equation (1).
template <typename T>
Vector3<T> PredictScaleMisalignmentAccel(const ImuIntrinsics<T>& p,
                                         const BodyMotion<T>& motion,
                                         const Vector3<T>& b_a) {
  return p.M_a * (p.C_i_b * SpecificForceAtPoint(motion, p.r_b)) + b_a;
}

// Equation (2).
template <typename T>
Vector3<T> PredictScaleMisalignmentGyro(const ImuIntrinsics<T>& p,
                                        const BodyMotion<T>& motion,
                                        const Vector3<T>& b_g) {
  const Matrix3<T> C_gyro_b = p.C_gyro_i * p.C_i_b;
  return p.M_g * (C_gyro_b * motion.w_b) + p.A * (C_gyro_b * SpecificForceAtPoint(motion, p.r_b)) +
         b_g;
}

// Equation (1) and its Jacobians (J may be nullptr).
inline Eigen::Vector3d PredictScaleMisalignmentAccel(const ImuIntrinsicsd& p,
                                                     const BodyMotion<double>& motion,
                                                     const Eigen::Vector3d& b_a,
                                                     ImuAccelJacobians* J) {
  const Eigen::Vector3d f = SpecificForceAtPoint(motion, p.r_b);
  const Eigen::Vector3d f_i = p.C_i_b * f;
  if (J != nullptr) {
    const Eigen::Matrix3d MC = p.M_a * p.C_i_b;
    *J = ImuAccelJacobians();
    J->w_b = MC * CentripetalJacobian(motion.w_b, p.r_b);
    J->dw_b = -MC * Hat(p.r_b);
    J->f_b = MC;
    J->r_b = MC * LeverArmJacobian(motion.w_b, motion.dw_b);
    J->phi_i_b = -MC * Hat(f);
    J->M_a = LowerTriangularProductJacobian(f_i);
  }
  return p.M_a * f_i + b_a;
}

// Equation (2) and its Jacobians (J may be nullptr).
inline Eigen::Vector3d PredictScaleMisalignmentGyro(const ImuIntrinsicsd& p,
                                                    const BodyMotion<double>& motion,
                                                    const Eigen::Vector3d& b_g,
                                                    ImuGyroJacobians* J) {
  const Eigen::Matrix3d C_gyro_b = p.C_gyro_i * p.C_i_b;
  const Eigen::Vector3d f = SpecificForceAtPoint(motion, p.r_b);
  const Eigen::Vector3d w_gyro = C_gyro_b * motion.w_b;
  const Eigen::Vector3d f_gyro = C_gyro_b * f;
  if (J != nullptr) {
    const Eigen::Matrix3d MC = p.M_g * C_gyro_b;
    const Eigen::Matrix3d AC = p.A * C_gyro_b;
    *J = ImuGyroJacobians();
    J->w_b = MC + AC * CentripetalJacobian(motion.w_b, p.r_b);
    J->dw_b = -AC * Hat(p.r_b);
    J->f_b = AC;
    J->r_b = AC * LeverArmJacobian(motion.w_b, motion.dw_b);
    J->phi_i_b = -(MC * Hat(motion.w_b) + AC * Hat(f));
    J->phi_gyro_i =
        -(p.M_g * p.C_gyro_i * Hat(p.C_i_b * motion.w_b) + p.A * p.C_gyro_i * Hat(p.C_i_b * f));
    J->M_g = LowerTriangularProductJacobian(w_gyro);
    J->A = FullMatrixProductJacobian(f_gyro);
  }
  return p.M_g * w_gyro + p.A * f_gyro + b_g;
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_SCALE_MISALIGNMENT_MODEL_H_
