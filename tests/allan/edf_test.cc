#include "splinecal/allan/edf.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <random>
#include <vector>

#include "splinecal/allan/work_budget.h"

namespace splinecal {
namespace {

constexpr PowerLawNoise kAllNoiseTypes[] = {PowerLawNoise::kWhitePm,
                                            PowerLawNoise::kFlickerPm,
                                            PowerLawNoise::kWhiteFm,
                                            PowerLawNoise::kFlickerFm,
                                            PowerLawNoise::kRandomWalkFm};

// White FM (white rate noise): the correlation of the second differences d_k and d_{k+j} of the
// integrated signal. d_k = sum of y over [k + m, k + 2m) minus the sum over [k, k + m), so
// Cov(d_k, d_{k+j}) / sigma^2 counts the overlap of two such +-1 windows j apart: 2m - 3|j| for
// |j| <= m (two like-signed overlaps of m - |j| and one opposite of |j|), |j| - 2m for
// m <= |j| <= 2m (the + half of the first on the - half of the second), 0 beyond; Var = 2m.
double WhiteFmCorrelation(int64_t j, int64_t m) {
  j = std::abs(j);
  if (j <= m) return 1.0 - 1.5 * static_cast<double>(j) / static_cast<double>(m);
  if (j <= 2 * m) return static_cast<double>(j - 2 * m) / static_cast<double>(2 * m);
  return 0.0;
}

// The exact EDF of the mean of the T squared terms d_0, d_s, d_2s, ... (zero-mean Gaussians of
// one variance, correlation rho): Var(d_a^2, d_b^2) = 2 Cov(d_a, d_b)^2, so with
// edf = 2 E^2 / Var,  edf = T^2 / sum_{i,j < T} rho((i - j) s)^2.
double ExactWhiteFmEdf(int64_t n, int64_t m, int64_t stride) {
  const int64_t terms = AllanTermCount(n, m, stride);
  double sum = static_cast<double>(terms);  // i = j
  for (int64_t lag = 1; lag < terms && lag * stride < 2 * m; ++lag) {
    const double rho = WhiteFmCorrelation(lag * stride, m);
    sum += 2.0 * static_cast<double>(terms - lag) * rho * rho;
  }
  return static_cast<double>(terms) * static_cast<double>(terms) / sum;
}

TEST(StridedAllanEdf, StrideOneIsTheOverlappingEdf) {
  for (const PowerLawNoise noise : kAllNoiseTypes) {
    for (const int64_t m : {1, 7, 100, 5000}) {
      EXPECT_EQ(StridedAllanEdf(noise, 10000, m, 1), OverlappingAllanEdf(noise, 10000, m));
    }
  }
}

// For stride >= 2m + 1 the terms of white PM, white FM and random-walk FM share no sample: the
// mean of T independent chi^2(1) terms has exactly T degrees of freedom, fewer than the
// overlapping estimator's, so the rule gives T.
TEST(StridedAllanEdf, DisjointTermsGiveTheirCount) {
  constexpr int64_t kN = 1000000;
  for (const PowerLawNoise noise :
       {PowerLawNoise::kWhitePm, PowerLawNoise::kWhiteFm, PowerLawNoise::kRandomWalkFm}) {
    for (const int64_t m : {1, 3, 50, 1000}) {
      for (const int64_t stride : {2 * m + 1, 4 * m, 64 * m}) {
        const double terms = static_cast<double>(AllanTermCount(kN, m, stride));
        EXPECT_EQ(StridedAllanEdf(noise, kN, m, stride), terms) << "m " << m << " s " << stride;
      }
    }
  }
  // Never below one degree of freedom, never above the overlapping EDF.
  EXPECT_EQ(StridedAllanEdf(PowerLawNoise::kWhiteFm, 1000, 400, 512), kMinimumEdf);
  EXPECT_EQ(StridedAllanEdf(PowerLawNoise::kRandomWalkFm, 1000, 100, 2),
            OverlappingAllanEdf(PowerLawNoise::kRandomWalkFm, 1000, 100));
}

// The exact white-FM EDF above checked by simulation: 4000 records of white noise, the strided
// estimate of each, edf = 2 mean^2 / variance. Its relative sampling error is sqrt(2 / 4000) =
// 2.2% (for the variance of a nearly Gaussian estimate), so 10% is 4.5 sigma; the rule's 1.5
// times at s = m is far outside that.
TEST(StridedAllanEdf, ExactWhiteFmEdfMatchesSimulation) {
  constexpr int64_t kN = 2000;
  constexpr int kRecords = 4000;
  constexpr double kSamplingTolerance = 0.10;
  std::mt19937_64 engine(29);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (const auto& [m, stride] :
       std::vector<std::pair<int64_t, int64_t>>{{8, 8}, {8, 2}, {4, 12}}) {
    std::vector<double> estimates;
    std::vector<double> theta(kN + 1);
    for (int record = 0; record < kRecords; ++record) {
      theta[0] = 0.0;
      for (int64_t k = 0; k < kN; ++k) theta[k + 1] = theta[k] + normal(engine);
      double sum = 0.0;
      for (int64_t k = 0; k + 2 * m <= kN; k += stride) {
        const double d = theta[k + 2 * m] - 2.0 * theta[k + m] + theta[k];
        sum += d * d;
      }
      estimates.push_back(sum / static_cast<double>(AllanTermCount(kN, m, stride)));
    }
    double mean = 0.0;
    for (const double e : estimates) mean += e / kRecords;
    double variance = 0.0;
    for (const double e : estimates) variance += (e - mean) * (e - mean) / (kRecords - 1);
    const double simulated = 2.0 * mean * mean / variance;
    EXPECT_NEAR(ExactWhiteFmEdf(kN, m, stride) / simulated, 1.0, kSamplingTolerance)
        << "m " << m << " s " << stride;
  }
}

// The rule against the exact white-FM EDF over m = 1 .. 10^4 and s = 1 .. 4096: never
// pessimistic, at worst 1.5 times optimistic, at s = m (allan/edf.h).
TEST(StridedAllanEdf, RuleAgainstExactWhiteFmEdf) {
  constexpr int64_t kN = 1000000;
  // Riley's simple white-FM formula against the exact EDF of the overlapping estimator: an
  // approximation, off by 7e-7 at m = 1 and 1.7e-3 at m = N / 100 (measured here).
  constexpr double kFormulaTolerance = 2e-3;
  std::vector<int64_t> sizes;
  for (int64_t m = 1; m <= 64; ++m) sizes.push_back(m);
  for (const int64_t m : {100, 128, 333, 1000, 1024, 4096, 10000}) sizes.push_back(m);
  double worst = 2.0;
  int64_t worst_m = 0;
  int64_t worst_stride = 0;
  double worst_beyond_2m = 2.0;
  double worst_below_quarter = 2.0;
  for (const int64_t m : sizes) {
    const double overlapping = OverlappingAllanEdf(PowerLawNoise::kWhiteFm, kN, m);
    EXPECT_NEAR(ExactWhiteFmEdf(kN, m, 1) / overlapping, 1.0, kFormulaTolerance) << "m " << m;
    for (int64_t stride = 2; stride <= 4096; ++stride) {
      const double ratio =
          ExactWhiteFmEdf(kN, m, stride) / StridedAllanEdf(PowerLawNoise::kWhiteFm, kN, m, stride);
      // Never pessimistic (beyond the approximation of Riley's formula).
      EXPECT_LE(ratio, 1.0 + kFormulaTolerance) << "m " << m << " s " << stride;
      if (ratio < worst) {
        worst = ratio;
        worst_m = m;
        worst_stride = stride;
      }
      if (stride >= 2 * m) worst_beyond_2m = std::min(worst_beyond_2m, ratio);
      if (4 * stride <= m) worst_below_quarter = std::min(worst_below_quarter, ratio);
    }
  }
  std::printf(
      "worst exact / rule EDF ratio %.6f at m = %lld, s = %lld; %.6f for s >= 2m, %.6f "
      "for s <= m / 4\n",
      worst,
      static_cast<long long>(worst_m),
      static_cast<long long>(worst_stride),
      worst_beyond_2m,
      worst_below_quarter);
  // At s = m the neighbours correlate by rho(m) = -1/2: edf = T / (1 + 2/4) against the rule's T.
  EXPECT_NEAR(worst, 2.0 / 3.0, 1e-5);
  EXPECT_EQ(worst_stride, worst_m);
  EXPECT_NEAR(worst_beyond_2m, 1.0, 1e-9);
  EXPECT_GT(worst_below_quarter, 0.92);
}

}  // namespace
}  // namespace splinecal
