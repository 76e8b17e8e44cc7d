// Kalibr's `scale-misalignment-size-effect` accelerometer (IccScaledMisalignedSizeEffectImu in
// IccSensors.py; Rehder et al., ICRA 2016): each accelerometer axis k senses the specific force
// at its own position r_k (in the IMU frame i; r_x = 0 defines the IMU's origin), so row k of the
// reading takes the rigid-body terms at r_k:
//
//     v   = C_i_b f_b(r_b) + sum_k e_k e_k^T (dw_i x r_k + w_i x (w_i x r_k)),          (1)
//           w_i = C_i_b w_b, dw_i = C_i_b dw_b, r_k in {0, ry_i, rz_i},
//     accel = M_a v + b_a.
//
// Kalibr writes row k as I_k C_i_b (dw_b x r_k_b + w_b x (w_b x r_k_b)) with
// r_k_b = r_b + C_i_b^T r_k: the same, as C (a x b) = (C a) x (C b). Its gyro is the
// scale-misalignment gyro (the class does not override it): g-sensitivity sees f_b(r_b).
//
// Jacobians (right perturbation; D and L from imu/rigid_body_point.h; P_k = e_k e_k^T):
//     dv/dw_b     = C_i_b D(w_b, r_b) + sum_k P_k D(w_i, r_k) C_i_b
//     dv/ddw_b    = -C_i_b [r_b]x - sum_k P_k [r_k]x C_i_b
//     dv/df_b     = C_i_b,          dv/dr_b = C_i_b L(w_b, dw_b)
//     dv/dphi_i_b = -C_i_b [f_b(r_b)]x + sum_k P_k ([r_k]x C_i_b [dw_b]x - D(w_i, r_k) C_i_b
//     [w_b]x) dv/dr_k     = P_k L(w_i, dw_i)
// and d accel = M_a dv, d accel/dM_a = LowerTriangularProductJacobian(v).
#ifndef SPLINECAL_IMU_SIZE_EFFECT_MODEL_H_
#define SPLINECAL_IMU_SIZE_EFFECT_MODEL_H_

#include <Eigen/Core>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// Equation (1)'s v: the specific force each axis senses, in i, before M_a.
template <typename T>
Vector3<T> SizeEffectSpecificForce(const ImuIntrinsics<T>& p, const BodyMotion<T>& motion) {
  Vector3<T> v = p.C_i_b * SpecificForceAtPoint(motion, p.r_b);
  const Vector3<T> w_i = p.C_i_b * motion.w_b;
  const Vector3<T> dw_i = p.C_i_b * motion.dw_b;
  v(1) += (dw_i.cross(p.ry_i) + w_i.cross(w_i.cross(p.ry_i)))(1);
  v(2) += (dw_i.cross(p.rz_i) + w_i.cross(w_i.cross(p.rz_i)))(2);
  return v;
}

template <typename T>
Vector3<T> PredictSizeEffectAccel(const ImuIntrinsics<T>& p,
                                  const BodyMotion<T>& motion,
                                  const Vector3<T>& b_a) {
  return p.M_a * SizeEffectSpecificForce(p, motion) + b_a;
}

// The same and its Jacobians (J may be nullptr).
inline Eigen::Vector3d PredictSizeEffectAccel(const ImuIntrinsicsd& p,
                                              const BodyMotion<double>& motion,
                                              const Eigen::Vector3d& b_a,
                                              ImuAccelJacobians* J) {
  const Eigen::Vector3d v = SizeEffectSpecificForce(p, motion);
  if (J != nullptr) {
    const Eigen::Vector3d f = SpecificForceAtPoint(motion, p.r_b);
    const Eigen::Vector3d w_i = p.C_i_b * motion.w_b;
    const Eigen::Vector3d dw_i = p.C_i_b * motion.dw_b;
    const Eigen::Matrix3d L_i = LeverArmJacobian(w_i, dw_i);
    Eigen::Matrix3d dv_dw = p.C_i_b * CentripetalJacobian(motion.w_b, p.r_b);
    Eigen::Matrix3d dv_ddw = -p.C_i_b * Hat(p.r_b);
    Eigen::Matrix3d dv_dphi = -p.C_i_b * Hat(f);
    const Eigen::Matrix3d C_dw_x = p.C_i_b * Hat(motion.dw_b);
    const Eigen::Matrix3d C_w_x = p.C_i_b * Hat(motion.w_b);
    const int axes[2] = {1, 2};
    const Eigen::Vector3d* arms[2] = {&p.ry_i, &p.rz_i};
    Eigen::Matrix3d dv_dr[2];
    for (int n = 0; n < 2; ++n) {
      const int k = axes[n];
      const Eigen::Vector3d& r_k = *arms[n];
      const Eigen::Matrix3d D_k = CentripetalJacobian(w_i, r_k);
      const Eigen::Matrix3d r_k_x = Hat(r_k);
      dv_dw.row(k) += D_k.row(k) * p.C_i_b;
      dv_ddw.row(k) -= r_k_x.row(k) * p.C_i_b;
      dv_dphi.row(k) += r_k_x.row(k) * C_dw_x - D_k.row(k) * C_w_x;
      dv_dr[n].setZero();
      dv_dr[n].row(k) = L_i.row(k);
    }
    *J = ImuAccelJacobians();
    J->w_b = p.M_a * dv_dw;
    J->dw_b = p.M_a * dv_ddw;
    J->f_b = p.M_a * p.C_i_b;
    J->r_b = p.M_a * p.C_i_b * LeverArmJacobian(motion.w_b, motion.dw_b);
    J->phi_i_b = p.M_a * dv_dphi;
    J->M_a = LowerTriangularProductJacobian(v);
    J->ry_i = p.M_a * dv_dr[0];
    J->rz_i = p.M_a * dv_dr[1];
  }
  return p.M_a * v + b_a;
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_SIZE_EFFECT_MODEL_H_
