// One IMU's model parameters (Kalibr's IccImu / IccScaledMisalignedImu /
// IccScaledMisalignedSizeEffectImu design variables, IccSensors.py) and the layout of the
// models' analytic Jacobians (imu/imu_intrinsic_model.h; docs/imu_models.md).
//
// Frames: b is the spline's body frame, which is the reference IMU's (the first IMU's)
// accelerometer frame; i is this IMU's accelerometer frame; gyro is its gyroscope triad's frame.
// T_i_b = (C_i_b, -C_i_b r_b) as Kalibr writes it (IccImu.getTransformationFromBodyToImu): r_b is
// this IMU's origin in b. The reference IMU has C_i_b = I, r_b = 0, held fixed.
#ifndef SPLINECAL_IMU_IMU_INTRINSICS_H_
#define SPLINECAL_IMU_IMU_INTRINSICS_H_

#include <Eigen/Core>

#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/lie/types.h"

namespace splinecal {

// Every field at its nominal value by default: that is the `calibrated` model with the IMU at
// the body origin. The models read only their own fields (imu/imu_intrinsic_model.h).
template <typename T>
struct ImuIntrinsics {
  Matrix3<T> C_i_b = Matrix3<T>::Identity();     // rotation b -> i
  Vector3<T> r_b = Vector3<T>::Zero();           // origin of i in b [m]
  Matrix3<T> M_a = Matrix3<T>::Identity();       // accelerometer scale/misalignment, lower tri.
  Matrix3<T> M_g = Matrix3<T>::Identity();       // gyroscope scale/misalignment, lower tri.
  Matrix3<T> A = Matrix3<T>::Zero();             // g-sensitivity [(rad/s)/(m/s^2)]
  Matrix3<T> C_gyro_i = Matrix3<T>::Identity();  // rotation i -> gyro
  Vector3<T> ry_i = Vector3<T>::Zero();          // y accelerometer's position in i [m]
  Vector3<T> rz_i = Vector3<T>::Zero();          // z accelerometer's position in i [m]
  // rx_i, the x accelerometer's position, is 0 by definition: it is the IMU's origin (Kalibr
  // holds it fixed at 0, IccScaledMisalignedSizeEffectImu.addDesignVariables).

  template <typename U>
  ImuIntrinsics<U> cast() const {
    ImuIntrinsics<U> out;
    out.C_i_b = C_i_b.template cast<U>();
    out.r_b = r_b.template cast<U>();
    out.M_a = M_a.template cast<U>();
    out.M_g = M_g.template cast<U>();
    out.A = A.template cast<U>();
    out.C_gyro_i = C_gyro_i.template cast<U>();
    out.ry_i = ry_i.template cast<U>();
    out.rz_i = rz_i.template cast<U>();
    return out;
  }
};

using ImuIntrinsicsd = ImuIntrinsics<double>;

// One IMU of a rig as Kalibr's imu-*.yaml describes it (imuN: model, T_i_b, time_offset,
// accelerometers, gyroscopes): its model, the model's parameters, and its clock offset to the
// reference IMU, Kalibr's `time_offset` [s]: a reading stamped t senses the motion at
// t + time_offset on the reference (spline) clock (IccImu: tk = stamp + timeOffset).
struct ImuCalibration {
  ImuModelKind model = ImuModelKind::kCalibrated;
  ImuIntrinsicsd intrinsics;
  double time_offset_s = 0.0;
};

// d accel / d (each input). Rotations are perturbed on the RIGHT, C -> C Exp(phi) (splinecal's
// one convention, lie/se3.h). A block the model does not depend on is zero. d accel / d b_a = I.
struct ImuAccelJacobians {
  Eigen::Matrix3d w_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dw_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d f_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d phi_i_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d r_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, kLowerTriangularParameters> M_a =
      Eigen::Matrix<double, 3, kLowerTriangularParameters>::Zero();
  Eigen::Matrix3d ry_i = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rz_i = Eigen::Matrix3d::Zero();
};

// d gyro / d (each input), the same conventions. d gyro / d b_g = I.
struct ImuGyroJacobians {
  Eigen::Matrix3d w_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d dw_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d f_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d phi_i_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d r_b = Eigen::Matrix3d::Zero();
  Eigen::Matrix<double, 3, kLowerTriangularParameters> M_g =
      Eigen::Matrix<double, 3, kLowerTriangularParameters>::Zero();
  Eigen::Matrix<double, 3, kFullMatrixParameters> A =
      Eigen::Matrix<double, 3, kFullMatrixParameters>::Zero();
  Eigen::Matrix3d phi_gyro_i = Eigen::Matrix3d::Zero();
};

}  // namespace splinecal

#endif  // SPLINECAL_IMU_IMU_INTRINSICS_H_
