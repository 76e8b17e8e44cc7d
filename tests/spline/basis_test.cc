#include "splinecal/spline/basis.h"

#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <Eigen/Core>
#include <array>
#include <cmath>

namespace splinecal {
namespace {

// The basis is a cubic polynomial with coefficients k/6: evaluations agree to rounding.
constexpr double kPolynomialTolerance = 1e-14;
// Central differences of a cubic with h = 1e-5: truncation h^2/6 |B'''| <= 1e-10, rounding
// eps / h ~ 2e-11.
constexpr double kCentralDifferenceTolerance = 1e-9;

// Uniform B-spline basis function of control point m, degree p, by the Cox-de Boor recursion,
// with knots tau_k = k - 2 so that N_m (cubic) is centred on t_m = m and active on [m-2, m+2).
double CoxDeBoor(int m, int p, double s) {
  const double tau_m = m - 2.0;
  if (p == 0) return (s >= tau_m && s < tau_m + 1.0) ? 1.0 : 0.0;
  const double left = (s - tau_m) / p * CoxDeBoor(m, p - 1, s);
  const double right = (tau_m + p + 1.0 - s) / p * CoxDeBoor(m + 1, p - 1, s);
  return left + right;
}

TEST(CumulativeBlendingMatrix, EqualsConventionsLiteral) {
  Eigen::Matrix4d expected;
  // clang-format off
  expected << 6, 0,  0,  0,
              5, 3, -3,  1,
              1, 3,  3, -2,
              0, 0,  0,  1;
  // clang-format on
  expected /= 6.0;
  EXPECT_EQ(CumulativeBlendingMatrix(), expected);
}

TEST(CumulativeBasis, IsCumulativeSumOfCoxDeBoorBasis) {
  const int segment = 5;  // t in [t_5, t_6): control points 4..7
  for (double u = 0.0; u < 1.0; u += 0.0625) {
    const double s = segment + u;
    std::array<double, 4> B;
    for (int m = 0; m < 4; ++m) B[m] = CoxDeBoor(segment - 1 + m, 3, s);
    const Eigen::Vector4d Bt = CumulativeBasis<0>(u);
    for (int j = 0; j < 4; ++j) {
      double cumulative = 0.0;
      for (int m = j; m < 4; ++m) cumulative += B[m];
      EXPECT_NEAR(Bt[j], cumulative, kPolynomialTolerance) << "u = " << u << ", j = " << j;
    }
  }
}

TEST(CumulativeBasis, FirstCoefficientIsOneAndDerivativesZero) {
  for (double u : {0.0, 0.3, 1.0}) {
    EXPECT_EQ(CumulativeBasis<0>(u)[0], 1.0);
    EXPECT_EQ(CumulativeBasis<1>(u)[0], 0.0);
    EXPECT_EQ(CumulativeBasis<2>(u)[0], 0.0);
  }
}

TEST(CumulativeBasis, EndValuesMatchNextSegmentStart) {
  // C2 continuity of the basis: Omega_{i+j-1} is blended by Bt_j in segment i and by Bt_{j-1}
  // in segment i+1, so Bt_j(1) = Bt_{j-1}(0) for j = 2, 3 (value and both derivatives). Bt_1(1) =
  // 1 with zero derivatives turns T_{i-1} Exp(Omega_i) into T_i, the next segment's first pose,
  // and Bt_3(0) = 0 (with zero derivatives) leaves out the next segment's new Omega.
  const Eigen::Vector4d end0 = CumulativeBasis<0>(1.0);
  const Eigen::Vector4d start0 = CumulativeBasis<0>(0.0);
  const Eigen::Vector4d end1 = CumulativeBasis<1>(1.0);
  const Eigen::Vector4d start1 = CumulativeBasis<1>(0.0);
  const Eigen::Vector4d end2 = CumulativeBasis<2>(1.0);
  const Eigen::Vector4d start2 = CumulativeBasis<2>(0.0);
  EXPECT_NEAR(end0[1], 1.0, kPolynomialTolerance);
  EXPECT_NEAR(end1[1], 0.0, kPolynomialTolerance);
  EXPECT_NEAR(end2[1], 0.0, kPolynomialTolerance);
  for (int j = 2; j < 4; ++j) {
    EXPECT_NEAR(end0[j], start0[j - 1], kPolynomialTolerance) << j;
    EXPECT_NEAR(end1[j], start1[j - 1], kPolynomialTolerance) << j;
    EXPECT_NEAR(end2[j], start2[j - 1], kPolynomialTolerance) << j;
  }
  EXPECT_NEAR(start0[3], 0.0, kPolynomialTolerance);
  EXPECT_NEAR(start1[3], 0.0, kPolynomialTolerance);
  EXPECT_NEAR(start2[3], 0.0, kPolynomialTolerance);
}

TEST(CumulativeBasis, DerivativesMatchCentralDifferences) {
  const double h = 1e-5;
  for (double u : {0.0, 0.2, 0.5, 0.77, 1.0}) {
    const Eigen::Vector4d d1 = (CumulativeBasis<0>(u + h) - CumulativeBasis<0>(u - h)) / (2 * h);
    const Eigen::Vector4d d2 = (CumulativeBasis<1>(u + h) - CumulativeBasis<1>(u - h)) / (2 * h);
    EXPECT_LT((CumulativeBasis<1>(u) - d1).lpNorm<Eigen::Infinity>(), kCentralDifferenceTolerance);
    EXPECT_LT((CumulativeBasis<2>(u) - d2).lpNorm<Eigen::Infinity>(), kCentralDifferenceTolerance);
  }
}

TEST(CumulativeBasis, JetCarriesDerivativeInU) {
  using Jet = ceres::Jet<double, 1>;
  const Jet u(0.4, 0);
  const Eigen::Matrix<Jet, 4, 1> Bt = CumulativeBasis<0>(u);
  const Eigen::Vector4d d1 = CumulativeBasis<1>(0.4);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(Bt[j].a, CumulativeBasis<0>(0.4)[j], kPolynomialTolerance);
    EXPECT_NEAR(Bt[j].v[0], d1[j], kPolynomialTolerance);
  }
}

// The split model's position weights: the ordinary B-spline basis (Cox-de Boor), a partition of
// unity, whose derivatives are the differences of the cumulative basis' derivatives.
TEST(BasisFromCumulative, IsTheCoxDeBoorBasisAndItsDerivatives) {
  const int segment = 5;
  for (double u = 0.0; u < 1.0; u += 0.0625) {
    const Eigen::Vector4d B = BasisFromCumulative<double>(CumulativeBasis<0>(u));
    for (int m = 0; m < 4; ++m) {
      EXPECT_NEAR(B[m], CoxDeBoor(segment - 1 + m, 3, segment + u), kPolynomialTolerance);
    }
    EXPECT_NEAR(B.sum(), 1.0, kPolynomialTolerance);
    for (const Eigen::Vector4d& derivative : {BasisFromCumulative<double>(CumulativeBasis<1>(u)),
                                              BasisFromCumulative<double>(CumulativeBasis<2>(u))}) {
      EXPECT_NEAR(derivative.sum(), 0.0, kPolynomialTolerance);
    }
    const double h = 1e-5;
    const Eigen::Vector4d numeric = (BasisFromCumulative<double>(CumulativeBasis<0>(u + h)) -
                                     BasisFromCumulative<double>(CumulativeBasis<0>(u - h))) /
                                    (2.0 * h);
    EXPECT_TRUE((BasisFromCumulative<double>(CumulativeBasis<1>(u)) - numeric).norm() <
                kCentralDifferenceTolerance);
  }
}

}  // namespace
}  // namespace splinecal
