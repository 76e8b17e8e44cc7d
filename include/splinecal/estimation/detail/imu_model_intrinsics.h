// The definition of ImuModelParameters::Intrinsics<T> (estimation/imu_model_parameters.h), for
// the translation units that instantiate it: the library's IMU-model costs for double
// (src/estimation/imu_model_costs.cc) and the tests' automatic-differentiation oracle for Jets
// (tests/testing/autodiff_imu_model_costs.h).
#ifndef SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_INTRINSICS_H_
#define SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_INTRINSICS_H_

#include <Eigen/Core>

#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

namespace splinecal {

template <typename T>
ImuIntrinsics<T> ImuModelParameters::Intrinsics(
    const T* m_a, const T* m_g, const T* a, const T* phi_gyro_i, const T* ry_i, const T* rz_i) {
  ImuIntrinsics<T> p;
  p.M_a = LowerTriangularFromParameters(m_a);
  p.M_g = LowerTriangularFromParameters(m_g);
  p.A = FullMatrixFromParameters(a);
  p.C_gyro_i = SO3<T>::Exp(Eigen::Map<const Vector3<T>>(phi_gyro_i)).matrix();
  p.ry_i = Eigen::Map<const Vector3<T>>(ry_i);
  p.rz_i = Eigen::Map<const Vector3<T>>(rz_i);
  return p;
}

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_DETAIL_IMU_MODEL_INTRINSICS_H_
