// The parameter vectors behind the IMU models' matrices (docs/conventions.md "IMU models"), and
// the Jacobians of a matrix-vector product with respect to them.
//
//   M (M_a, M_g): lower triangular, Kalibr's MatrixBasicDv pattern [[1,0,0],[1,1,0],[1,1,1]]
//                 (IccSensors.py, IccScaledMisalignedImu.addDesignVariables); 6 parameters in
//                 row-major order m = (M00, M10, M11, M20, M21, M22), nominal M = I.
//   A:            full 3x3 (9 parameters, row-major a = (A00, A01, ..., A22)), nominal A = 0.
//
// For y = M v:  dy_r / dM_rc = v_c, so d(M v)/dm has v's entries along each row at the columns of
// that row's parameters; likewise d(A v)/da = [v^T 0 0; 0 v^T 0; 0 0 v^T].
#ifndef SPLINECAL_IMU_MATRIX_PARAMETERS_H_
#define SPLINECAL_IMU_MATRIX_PARAMETERS_H_

#include <Eigen/Core>

#include "splinecal/lie/types.h"

namespace splinecal {

inline constexpr int kLowerTriangularParameters = 6;
inline constexpr int kFullMatrixParameters = 9;

// Column of parameter (row, col) in m, for col <= row: rows start at 0, 1, 3.
inline constexpr int LowerTriangularIndex(int row, int col) { return row * (row + 1) / 2 + col; }

template <typename T>
Matrix3<T> LowerTriangularFromParameters(const T* m) {
  Matrix3<T> M = Matrix3<T>::Zero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) M(r, c) = m[LowerTriangularIndex(r, c)];
  }
  return M;
}

// The lower triangle of M into m (the upper triangle is not a parameter and is ignored).
template <typename T>
void LowerTriangularToParameters(const Matrix3<T>& M, T* m) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) m[LowerTriangularIndex(r, c)] = M(r, c);
  }
}

template <typename T>
Matrix3<T> FullMatrixFromParameters(const T* a) {
  return Eigen::Map<const Eigen::Matrix<T, 3, 3, Eigen::RowMajor>>(a);
}

template <typename T>
void FullMatrixToParameters(const Matrix3<T>& A, T* a) {
  Eigen::Map<Eigen::Matrix<T, 3, 3, Eigen::RowMajor>> a_map(a);
  a_map = A;
}

// d(M v) / dm for lower-triangular M (3x6).
inline Eigen::Matrix<double, 3, kLowerTriangularParameters> LowerTriangularProductJacobian(
    const Eigen::Vector3d& v) {
  Eigen::Matrix<double, 3, kLowerTriangularParameters> J;
  J.setZero();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) J(r, LowerTriangularIndex(r, c)) = v(c);
  }
  return J;
}

// d(A v) / da for a full, row-major A (3x9).
inline Eigen::Matrix<double, 3, kFullMatrixParameters> FullMatrixProductJacobian(
    const Eigen::Vector3d& v) {
  Eigen::Matrix<double, 3, kFullMatrixParameters> J;
  J.setZero();
  for (int r = 0; r < 3; ++r) J.block<1, 3>(r, 3 * r) = v.transpose();
  return J;
}

}  // namespace splinecal

#endif  // SPLINECAL_IMU_MATRIX_PARAMETERS_H_
