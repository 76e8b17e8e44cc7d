// The parameters of Kalibr's scale-misalignment IMU models (imu/imu_intrinsic_model.h,
// docs/imu_models.md) as the estimator holds them: one block per matrix or vector, in the
// layouts of imu/matrix_parameters.h, nominal by default (the `calibrated` model).
// C_gyro_i = Exp(phi_gyro_i), a rotation vector about the nominal identity (Euclidean, so its
// standard deviation is in radians per axis). The IMU is the reference one (C_i_b = I, r_b = 0).
#ifndef SPLINECAL_ESTIMATION_IMU_MODEL_PARAMETERS_H_
#define SPLINECAL_ESTIMATION_IMU_MODEL_PARAMETERS_H_

#include <array>

#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/matrix_parameters.h"

namespace splinecal {

// The values of the model's parameter blocks, nominal by default (the `calibrated` model).
struct ImuModelParameters {
  std::array<double, kLowerTriangularParameters> m_a = {1.0, 0.0, 1.0, 0.0, 0.0, 1.0};
  std::array<double, kLowerTriangularParameters> m_g = {1.0, 0.0, 1.0, 0.0, 0.0, 1.0};
  std::array<double, kFullMatrixParameters> a = {};
  std::array<double, 3> phi_gyro_i = {};
  std::array<double, 3> ry_i = {};
  std::array<double, 3> rz_i = {};

  // As ImuIntrinsics (C_i_b = I, r_b = 0).
  template <typename T>
  static ImuIntrinsics<T> Intrinsics(const T* m_a,
                                     const T* m_g,
                                     const T* a,
                                     const T* phi_gyro_i,
                                     const T* ry_i,
                                     const T* rz_i);
  ImuIntrinsicsd Intrinsics() const;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_MODEL_PARAMETERS_H_
