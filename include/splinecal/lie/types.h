// Fixed-size Eigen aliases shared by the Lie-group layer (lie/so3.h, lie/se3.h) and its users.
//
// Every alias is a template on the scalar so that the same code runs with double and with
// ceres::Jet<double, N> (automatic differentiation).
#ifndef SPLINECAL_LIE_TYPES_H_
#define SPLINECAL_LIE_TYPES_H_

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace splinecal {

template <typename T>
using Vector3 = Eigen::Matrix<T, 3, 1>;
template <typename T>
using Vector4 = Eigen::Matrix<T, 4, 1>;
template <typename T>
using Vector6 = Eigen::Matrix<T, 6, 1>;
template <typename T>
using Matrix3 = Eigen::Matrix<T, 3, 3>;
template <typename T>
using Matrix4 = Eigen::Matrix<T, 4, 4>;
template <typename T>
using Matrix6 = Eigen::Matrix<T, 6, 6>;
template <typename T>
using Matrix3x6 = Eigen::Matrix<T, 3, 6>;
template <typename T>
using Matrix6x3 = Eigen::Matrix<T, 6, 3>;

using Vector6d = Vector6<double>;
using Matrix6d = Matrix6<double>;
using Matrix3x6d = Matrix3x6<double>;

}  // namespace splinecal

#endif  // SPLINECAL_LIE_TYPES_H_
