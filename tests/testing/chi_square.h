// Chi-square quantiles for the Monte-Carlo consistency (NEES) tests, the Mahalanobis NEES of an
// error with its covariance, and the check of per-group NEES sums against their 95% interval that
// those tests share.
//
// The sum of the normalised estimation errors squared over N independent runs of a d-dimensional
// estimate with an honest covariance is chi-square with N d degrees of freedom. Its quantiles
// come from the Wilson-Hilferty approximation [WilsonHilferty31]: (chi2_k / k)^(1/3) is nearly
// normal with mean 1 - 2/(9k) and variance 2/(9k), so
//
//     chi2_k(p) ~ k (1 - 2/(9k) + z_p sqrt(2/(9k)))^3,      z_p the standard normal quantile,
//
// with a relative error below 1e-3 for k >= 100 and below 0.2% at k = 20 (2.5% quantile of
// chi2_20: 9.591 tabulated, 9.575 here; 97.5%: 34.170 tabulated, 34.172 here).
//
// [WilsonHilferty31] E. B. Wilson, M. M. Hilferty, "The distribution of chi-square", PNAS 17(12),
// 1931.
#ifndef SPLINECAL_TESTS_TESTING_CHI_SQUARE_H_
#define SPLINECAL_TESTS_TESTING_CHI_SQUARE_H_

#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <vector>

#include "splinecal/allan/edf.h"

namespace splinecal {
namespace testing {

inline constexpr double kNormalQuantile975 = 1.959963984540054;  // z with P(Z < z) = 0.975

// Quantile of chi-square with k degrees of freedom at the standard normal quantile z.
inline double ChiSquareQuantile(double k, double z) {
  const double a = 2.0 / (9.0 * k);
  return k * std::pow(1.0 - a + z * std::sqrt(a), 3.0);
}

// The two-sided 95% interval of chi-square with k degrees of freedom.
struct ChiSquareInterval {
  double low = 0.0;
  double high = 0.0;
};

inline ChiSquareInterval ChiSquareInterval95(double k) {
  return {ChiSquareQuantile(k, -kNormalQuantile975), ChiSquareQuantile(k, kNormalQuantile975)};
}

// The two-sided interval of chi-square(k) that `groups` sums, each checked against its own, all
// hold at once with probability 95% or more when every covariance is honest (Bonferroni: each at
// level 1 - 0.05 / groups). A test asserting 8 groups against their 95% intervals would fail one
// by chance about a third of the time. The library's exact quantile (allan/edf.h): the
// Wilson-Hilferty form above loses accuracy in the far tails this reaches.
inline ChiSquareInterval ChiSquareFamilyInterval95(double k, int groups) {
  const double tail = 0.025 / static_cast<double>(groups);
  return {::splinecal::ChiSquareQuantile(tail, k), ::splinecal::ChiSquareQuantile(1.0 - tail, k)};
}

// A group of components of an estimate whose NEES is summed over the Monte-Carlo runs.
struct NeesGroup {
  const char* name;
  int first;  // index of its first component in the run's error vector
  int dof;
  double sum = 0.0;
};

// The squared Mahalanobis norm e^T Sigma^-1 e of an error e with covariance Sigma: its NEES, which
// is chi-square(dim e) for a Gaussian error whatever the correlations between its components.
// NaN when Sigma is not positive definite (LLT fails), so a test asserting on it fails.
inline double Mahalanobis(const Eigen::VectorXd& e, const Eigen::MatrixXd& sigma) {
  // Scaled to unit diagonal first: the entries of one group can differ by orders of magnitude
  // (A ~1e-4 rad/s per m/s^2 beside M_a ~1e-3), and the correlation matrix's factorisation
  // is then as well conditioned as the correlations allow.
  const Eigen::VectorXd s = sigma.diagonal().cwiseSqrt().cwiseInverse();
  const Eigen::LLT<Eigen::MatrixXd> llt(s.asDiagonal() * sigma * s.asDiagonal());
  if (llt.info() != Eigen::Success) return std::nan("");
  return llt.matrixL().solve(s.cwiseProduct(e)).squaredNorm();
}

// Prints each group's sum with its interval (ChiSquareInterval95 of runs x dof) and expects the
// sum inside it: below, the reported uncertainty is too pessimistic; above, overconfident.
inline void ExpectNeesSumsInsideInterval95(const std::vector<NeesGroup>& groups, int runs) {
  for (const NeesGroup& group : groups) {
    const ChiSquareInterval band = ChiSquareInterval95(runs * group.dof);
    std::printf(
        "%s: NEES sum %.2f over %d runs (mean %.3f per run, dof %d), 95%% interval [%.2f, %.2f]\n",
        group.name,
        group.sum,
        runs,
        group.sum / runs,
        group.dof,
        band.low,
        band.high);
    EXPECT_GE(group.sum, band.low) << group.name << ": uncertainty too pessimistic";
    EXPECT_LE(group.sum, band.high) << group.name << ": uncertainty overconfident";
  }
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_CHI_SQUARE_H_
