// The cumulative basis of the uniform cubic B-spline: blending coefficients Bt_j(u) and their
// derivatives.
//
// [CONVENTIONS "The spline"], [seed000 §3 eq. (2)], [Lovegrove13 §3.1]:
//
//     [Bt_0 Bt_1 Bt_2 Bt_3]^T = C [1 u u^2 u^3]^T,
//     C = 1/6 [[6, 0,  0,  0],
//              [5, 3, -3,  1],
//              [1, 3,  3, -2],
//              [0, 0,  0,  1]]
//
// Row j of C is the sum of rows j..3 of the uniform cubic B-spline matrix M (Bt_j = sum_{m>=j}
// B_m), so Bt_0 = 1 for every u. Derivatives come from one table: d^k/du^k u^n = n!/(n-k)! u^(n-k)
// (kPowerDerivativeFactor below), hence
//
//     d^k Bt / du^k = C [d^k/du^k (1, u, u^2, u^3)]^T,     d^k Bt / dt^k = (1/dt)^k d^k Bt / du^k.
//
// Everything is templated on the scalar so that u may be a ceres::Jet (a time offset estimated by
// automatic differentiation passes through u).
#ifndef SPLINECAL_SPLINE_BASIS_H_
#define SPLINECAL_SPLINE_BASIS_H_

#include <Eigen/Core>

namespace splinecal {

// Order of the spline (degree + 1): a segment depends on kSplineOrder control poses.
inline constexpr int kSplineOrder = 4;
// Highest time derivative of the basis that splinecal uses (acceleration).
inline constexpr int kMaxBasisDerivative = 2;

namespace internal {

// 6 * C, exactly as written in docs/conventions.md "The spline" (integers, so the table is exact in
// binary). clang-format off
inline constexpr double kCumulativeBasisTimes6[kSplineOrder][kSplineOrder] = {
    {6.0, 0.0,  0.0,  0.0},
    {5.0, 3.0, -3.0,  1.0},
    {1.0, 3.0,  3.0, -2.0},
    {0.0, 0.0,  0.0,  1.0}};
// clang-format on

// kPowerDerivativeFactor[k][n] = d^k/du^k u^n / u^(n-k) = n! / (n-k)!  (0 when k > n).
// clang-format off
inline constexpr double kPowerDerivativeFactor[kMaxBasisDerivative + 1][kSplineOrder] = {
    {1.0, 1.0, 1.0, 1.0},
    {0.0, 1.0, 2.0, 3.0},
    {0.0, 0.0, 2.0, 6.0}};
// clang-format on

}  // namespace internal

// The cumulative blending matrix C (4x4) of docs/conventions.md "The spline".
inline Eigen::Matrix4d CumulativeBlendingMatrix() {
  Eigen::Matrix4d C;
  for (int r = 0; r < kSplineOrder; ++r) {
    for (int c = 0; c < kSplineOrder; ++c) C(r, c) = internal::kCumulativeBasisTimes6[r][c] / 6.0;
  }
  return C;
}

// d^kDerivative/du^kDerivative of [1 u u^2 u^3]^T (kDerivative in 0..2).
template <int kDerivative, typename T>
Eigen::Matrix<T, kSplineOrder, 1> PowerBasis(const T& u) {
  static_assert(kDerivative >= 0 && kDerivative <= kMaxBasisDerivative,
                "PowerBasis: derivative order must be 0, 1 or 2");
  Eigen::Matrix<T, kSplineOrder, 1> powers;
  // u^(n-k) for n >= k, built by repeated multiplication (no pow(), Jet friendly).
  T u_power = T(1.0);
  for (int n = 0; n < kSplineOrder; ++n) {
    if (n < kDerivative) {
      powers[n] = T(0.0);
    } else {
      powers[n] = internal::kPowerDerivativeFactor[kDerivative][n] * u_power;
      u_power = u_power * u;
    }
  }
  return powers;
}

// d^kDerivative Bt / du^kDerivative at u: the cumulative blending coefficients (kDerivative = 0)
// or their u-derivatives. Entry 0 is Bt_0 (= 1, derivatives 0); entries 1..3 blend Omega_i,
// Omega_{i+1}, Omega_{i+2}. Divide by dt^kDerivative for time derivatives (see Segment).
template <int kDerivative, typename T>
Eigen::Matrix<T, kSplineOrder, 1> CumulativeBasis(const T& u) {
  const Eigen::Matrix<T, kSplineOrder, 1> powers = PowerBasis<kDerivative>(u);
  Eigen::Matrix<T, kSplineOrder, 1> coefficients;
  for (int r = 0; r < kSplineOrder; ++r) {
    T sum = T(0.0);
    for (int c = 0; c < kSplineOrder; ++c) {
      // The table's zeros are compile-time constants; the compiler drops those terms.
      if (internal::kCumulativeBasisTimes6[r][c] != 0.0) {
        sum += (internal::kCumulativeBasisTimes6[r][c] / 6.0) * powers[c];
      }
    }
    coefficients[r] = sum;
  }
  return coefficients;
}

// The ordinary (non-cumulative) B-spline weights from cumulative ones, B_j = Bt_j - Bt_{j+1}
// (Bt_4 = 0), since Bt_j = sum_{m>=j} B_m. The same difference holds for every derivative, so
// `cumulative` may be Bt or any of its time derivatives. Blending positions with them,
// sum_j B_j p_{i-1+j} = p_{i-1} + sum_{j>=1} Bt_j (p_{i-1+j} - p_{i-2+j}): the split model's
// position (spline/split_segment.h).
template <typename T>
Eigen::Matrix<T, kSplineOrder, 1> BasisFromCumulative(
    const Eigen::Matrix<T, kSplineOrder, 1>& cumulative) {
  Eigen::Matrix<T, kSplineOrder, 1> weights;
  for (int j = 0; j + 1 < kSplineOrder; ++j) weights[j] = cumulative[j] - cumulative[j + 1];
  weights[kSplineOrder - 1] = cumulative[kSplineOrder - 1];
  return weights;
}

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_BASIS_H_
