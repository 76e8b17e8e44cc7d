#include "splinecal/allan/allan_deviation.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "allan/static_series.h"
#include "splinecal/allan/edf.h"
#include "splinecal/allan/work_budget.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

// The bar (docs/allan.md, "Method", 1): the O(N) per-tau implementation equals the definition
// to 1e-10 relative.
// (Both sides are accurate to ~1e-13 here; see allan_deviation.h for the error budget.)
constexpr double kDefinitionTolerance = 1e-10;

// AVAR from its definition [IEEE952, annex C]: half the mean squared difference of the averages
// of two adjacent clusters of m samples, at every start k = 0 .. N - 2m; every cluster sum taken
// directly (O(N m)) in long double.
double DirectAllanVariance(const std::vector<double>& y, int64_t m) {
  const int64_t n = static_cast<int64_t>(y.size());
  long double total = 0.0L;
  for (int64_t k = 0; k + 2 * m <= n; ++k) {
    long double first = 0.0L;
    long double second = 0.0L;
    for (int64_t i = 0; i < m; ++i) {
      first += y[k + i];
      second += y[k + m + i];
    }
    const long double difference = (second - first) / m;
    total += difference * difference;
  }
  return static_cast<double>(total / (2.0L * (n - 2 * m + 1)));
}

// The same from long double prefix sums of the raw samples (no mean removal, no blocking): an
// independent O(N) reference for cluster sizes too large for the O(N m) loop.
double PrefixSumAllanVariance(const std::vector<double>& y, int64_t m) {
  const int64_t n = static_cast<int64_t>(y.size());
  std::vector<long double> prefix(n + 1, 0.0L);
  for (int64_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + y[i];
  long double total = 0.0L;
  for (int64_t k = 0; k + 2 * m <= n; ++k) {
    const long double d = prefix[k + 2 * m] - 2.0L * prefix[k + m] + prefix[k];
    total += d * d;
  }
  return static_cast<double>(total / (2.0L * m * m * (n - 2 * m + 1)));
}

// An accelerometer-like axis: gravity offset, white noise and a strong bias random walk (the
// drift makes the integrated signal large, the hard case for cumulative sums).
std::vector<double> AccelLikeAxis(int64_t n, uint64_t seed) {
  const testing::UnitDraws draws = testing::MakeUnitDraws(n, seed);
  return testing::StaticAxis(draws, 200.0, 2.0e-3, 3.0e-1, 9.81);
}

double RelativeDifference(double a, double b) { return std::abs(a - b) / std::abs(b); }

// AVAR from every stride-th start index k = 0, s, 2s, ... (allan_deviation.h), directly: long
// double prefix sums of the mean-removed samples (mean in long double), one term per start index.
double DirectStridedAllanVariance(const std::vector<double>& y, int64_t m, int64_t stride) {
  const int64_t n = static_cast<int64_t>(y.size());
  long double mean = 0.0L;
  for (const double v : y) mean += v;
  mean /= n;
  std::vector<long double> prefix(n + 1, 0.0L);
  for (int64_t i = 0; i < n; ++i) prefix[i + 1] = prefix[i] + (y[i] - mean);
  long double total = 0.0L;
  int64_t terms = 0;
  for (int64_t k = 0; k + 2 * m <= n; k += stride) {
    const long double d = prefix[k + 2 * m] - 2.0L * prefix[k + m] + prefix[k];
    total += d * d;
    ++terms;
  }
  return static_cast<double>(total / (2.0L * m * m * terms));
}

// A gyro-like axis: white noise and a bias random walk (ADIS16448 levels), 200 Hz.
std::vector<double> GyroLikeAxis(int64_t n, uint64_t seed) {
  const testing::UnitDraws draws = testing::MakeUnitDraws(n, seed);
  return testing::StaticAxis(draws, 200.0, 1.6968e-4, 1.9393e-5, 0.01);
}

TEST(OverlappingAllanDeviation, EqualsDirectDefinitionAtEveryClusterSize) {
  const std::vector<double> y = AccelLikeAxis(12000, 1);
  const std::vector<int64_t> sizes = AllanClusterSizes(12000, 10, 0.1);
  ASSERT_EQ(sizes.back(), 1000);
  const AllanCurve curve = OverlappingAllanDeviation(y, 200.0, sizes, "accel z");
  ASSERT_EQ(curve.adev.size(), sizes.size());
  for (size_t i = 0; i < sizes.size(); ++i) {
    const double direct = std::sqrt(DirectAllanVariance(y, sizes[i]));
    EXPECT_LE(RelativeDifference(curve.adev[i], direct), kDefinitionTolerance)
        << "m = " << sizes[i] << ": " << curve.adev[i] << " vs " << direct;
  }
}

// Cluster sizes on both sides of the near/far split of the implementation (2m = 131072), chunk
// boundaries, and m = N / 2 (a single difference).
TEST(OverlappingAllanDeviation, EqualsPrefixSumReferenceForLongClusters) {
  constexpr int64_t kN = 400000;
  const std::vector<double> y = AccelLikeAxis(kN, 2);
  const std::vector<int64_t> sizes = {
      1, 2, 7, 4096, 65535, 65536, 65537, 70001, 98304, 133333, 199999, 200000};
  const AllanCurve curve = OverlappingAllanDeviation(y, 200.0, sizes, "accel z");
  for (size_t i = 0; i < sizes.size(); ++i) {
    const double reference = std::sqrt(PrefixSumAllanVariance(y, sizes[i]));
    EXPECT_LE(RelativeDifference(curve.adev[i], reference), kDefinitionTolerance)
        << "m = " << sizes[i];
  }
}

TEST(OverlappingAllanDeviation, CurveEqualsSingleAllanVarianceBitForBit) {
  std::vector<double> y = AccelLikeAxis(2500000, 3);  // several segments of the near sweep
  const IntegratedSignal signal(std::move(y), 100.0, "gyro x");
  const std::vector<int64_t> sizes = {1, 10, 1000, 70000, 150000};
  const AllanCurve curve = signal.Deviation(sizes);
  // Threads share fixed tasks whose sums are combined in a fixed order: the same bits.
  EXPECT_EQ(signal.Deviation(sizes, 3).adev, curve.adev);
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(curve.adev[i], std::sqrt(signal.AllanVariance(sizes[i]))) << "m = " << sizes[i];
    EXPECT_DOUBLE_EQ(curve.tau_s[i], sizes[i] / 100.0);
  }
}

// y_k = a + b k: adjacent cluster averages differ by b m, so ADEV = |b| m / sqrt(2) exactly
// (the rate ramp term R^2 tau^2 / 2 with R = b f).
TEST(OverlappingAllanDeviation, LinearRampHasClosedForm) {
  constexpr double kSlopePerSample = 1e-3;
  std::vector<double> y(2000);
  for (size_t k = 0; k < y.size(); ++k) y[k] = 0.5 + kSlopePerSample * k;
  const std::vector<int64_t> sizes = {1, 3, 10, 100, 1000};
  const AllanCurve curve = OverlappingAllanDeviation(y, 50.0, sizes);
  for (size_t i = 0; i < sizes.size(); ++i) {
    // Rounding of the stored ramp (1e-16 of values ~2) against a difference of 1e-3 m.
    constexpr double kRampTolerance = 1e-9;
    EXPECT_LE(RelativeDifference(curve.adev[i], kSlopePerSample * sizes[i] / std::sqrt(2.0)),
              kRampTolerance)
        << "m = " << sizes[i];
  }
}

// White noise of density sigma: ADEV(tau) = sigma / sqrt(tau), within the error bars.
TEST(OverlappingAllanDeviation, WhiteNoiseFollowsMinusHalfSlope) {
  constexpr double kRate = 400.0;
  constexpr double kDensity = 0.05;
  const testing::UnitDraws draws = testing::MakeUnitDraws(1000000, 4);
  const std::vector<double> y = testing::StaticAxis(draws, kRate, kDensity, 0.0, -3.0);
  const std::vector<int64_t> sizes = AllanClusterSizes(1000000, 5, 0.01);
  const AllanCurve curve = OverlappingAllanDeviation(y, kRate, sizes);
  for (size_t i = 0; i < sizes.size(); ++i) {
    const double expected = kDensity / std::sqrt(curve.tau_s[i]);
    // Four error bars (the error bar is conservative for the overlapping estimator).
    EXPECT_NEAR(curve.adev[i], expected, 4.0 * curve.adev_error[i]) << "tau " << curve.tau_s[i];
  }
}

TEST(OverlappingAllanDeviation, ErrorBarsComeFromIndependentClusters) {
  const std::vector<double> y = AccelLikeAxis(1000, 5);
  const AllanCurve curve = OverlappingAllanDeviation(y, 10.0, {1, 3, 100, 500});
  EXPECT_DOUBLE_EQ(curve.adev_error[0], curve.adev[0] / std::sqrt(2.0 * 999));
  EXPECT_DOUBLE_EQ(curve.adev_error[1], curve.adev[1] / std::sqrt(2.0 * 332));
  EXPECT_DOUBLE_EQ(curve.adev_error[2], curve.adev[2] / std::sqrt(2.0 * 9));
  EXPECT_DOUBLE_EQ(curve.adev_error[3], curve.adev[3] / std::sqrt(2.0 * 1));
  EXPECT_EQ(AllanRelativeError(1000, 501), std::numeric_limits<double>::infinity());
}

// A constant adds nothing to a second difference: an offset of 1000 changes ADEV only by the
// rounding of the offset samples (1e-13 of the offset against noise of 1e-2).
TEST(OverlappingAllanDeviation, OffsetDoesNotChangeDeviation) {
  const testing::UnitDraws draws = testing::MakeUnitDraws(50000, 6);
  const std::vector<double> centred = testing::StaticAxis(draws, 100.0, 1e-3, 1e-3, 0.0);
  const std::vector<double> offset = testing::StaticAxis(draws, 100.0, 1e-3, 1e-3, 1000.0);
  const std::vector<int64_t> sizes = AllanClusterSizes(50000, 10, 0.5);
  const AllanCurve a = OverlappingAllanDeviation(centred, 100.0, sizes);
  const AllanCurve b = OverlappingAllanDeviation(offset, 100.0, sizes);
  constexpr double kOffsetTolerance = 1e-9;
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_LE(RelativeDifference(b.adev[i], a.adev[i]), kOffsetTolerance) << "m = " << sizes[i];
  }
}

TEST(OverlappingAllanDeviation, RateOnlyRescalesTau) {
  const std::vector<double> y = AccelLikeAxis(5000, 7);
  const AllanCurve slow = OverlappingAllanDeviation(y, 100.0, {1, 10, 100});
  const AllanCurve fast = OverlappingAllanDeviation(y, 400.0, {1, 10, 100});
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(slow.adev[i], fast.adev[i]);
    EXPECT_DOUBLE_EQ(slow.tau_s[i], 4.0 * fast.tau_s[i]);
  }
}

// The default path (every stride 1) is the overlapping estimator computed as before the budget,
// bit for bit, and agrees with the existing references.
TEST(StridedAllanDeviation, AllStridesOneIsTheOverlappingCurveBitForBit) {
  constexpr int64_t kN = 400000;
  const std::vector<double> y = AccelLikeAxis(kN, 8);
  const std::vector<int64_t> sizes = AllanClusterSizes(kN, 10, 0.1);
  const std::vector<int64_t> strides = AllanStrides(kN, sizes, kDefaultAllanMaxPasses);
  ASSERT_EQ(strides, std::vector<int64_t>(sizes.size(), 1));
  const IntegratedSignal signal(std::vector<double>(y), 200.0, "accel z");
  const AllanCurve plain = signal.Deviation(sizes, 2);
  const AllanCurve budgeted = signal.Deviation(sizes, strides, 2);
  EXPECT_EQ(budgeted.adev, plain.adev);
  EXPECT_EQ(budgeted.adev_error, plain.adev_error);
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_EQ(budgeted.adev[i], std::sqrt(signal.AllanVariance(sizes[i])));
    EXPECT_LE(RelativeDifference(budgeted.adev[i], std::sqrt(PrefixSumAllanVariance(y, sizes[i]))),
              kDefinitionTolerance);
    EXPECT_EQ(budgeted.num_terms[i], kN - 2 * sizes[i] + 1);
  }
}

// The strided sums (polyphase window, four sizes per kernel call) equal the strided definition.
// 1e-12: the kernel's block sums are within 6e-14 (second_differences.h); the rest is theta
// stored as double (2^-53 of |theta| ~ 1e3 sigma per term against a second difference of
// sigma sqrt(2m), averaging out over the terms; measured below 3e-14). Any term more or less
// would move the result by about 1 / T > 1e-6.
TEST(StridedAllanDeviation, EqualsDirectStridedSum) {
  constexpr int64_t kN = 300001;
  const std::vector<double> y = GyroLikeAxis(kN, 9);
  const std::vector<int64_t> sizes = AllanClusterSizes(kN, 100, 0.5);
  const IntegratedSignal signal(std::vector<double>(y), 200.0, "gyro x");
  // The budget's strides (8 passes: strides 64 and 32), and a hand-made mix around the window's
  // edges: stride 1 with the largest stride 64, m beyond the window, m = N / 2 (one term).
  const std::vector<int64_t> budget = AllanStrides(kN, sizes, 8);
  ASSERT_GT(budget.front(), 1);
  const std::vector<int64_t> mixed_sizes = {1, 2, 3, 63, 64, 65, 4097, 65536, 100000, 150000};
  const std::vector<int64_t> mixed_strides = {64, 1, 2, 64, 32, 8, 1, 16, 4, 64};
  for (const auto& [m_list, s_list] :
       {std::make_pair(sizes, budget), std::make_pair(mixed_sizes, mixed_strides)}) {
    const AllanCurve curve = signal.Deviation(m_list, s_list);
    ASSERT_EQ(curve.adev.size(), m_list.size());
    double worst = 0.0;
    for (size_t i = 0; i < m_list.size(); ++i) {
      const double direct = std::sqrt(DirectStridedAllanVariance(y, m_list[i], s_list[i]));
      worst = std::max(worst, RelativeDifference(curve.adev[i], direct));
      EXPECT_LE(RelativeDifference(curve.adev[i], direct), 1e-12)
          << "m = " << m_list[i] << ", stride " << s_list[i];
      EXPECT_EQ(curve.strides[i], s_list[i]);
      EXPECT_EQ(curve.num_terms[i], AllanTermCount(kN, m_list[i], s_list[i]));
    }
    std::printf("strided against direct: largest relative difference %.2e\n", worst);
    // Fixed segments summed in a fixed order: the same bits on any number of threads.
    EXPECT_EQ(signal.Deviation(m_list, s_list, 3).adev, curve.adev);
  }
}

// On simulated white noise plus a random walk, the strided deviation (4 passes of the budget,
// strides up to 128 at 100 per decade) lies around the exact (overlapping) one as its own
// interval says. The exact value is the mean of the strided estimates over all start phases,
// so strided - exact has less variance than the strided estimate itself: at 90% at most 10% of
// the points fall outside (allowed: 15%, the points being correlated), at 99.9% none.
TEST(StridedAllanDeviation, ExactCurveLiesWithinTheStridedIntervals) {
  constexpr int64_t kN = 1000000;
  const std::vector<double> y = GyroLikeAxis(kN, 10);
  const std::vector<int64_t> sizes = AllanClusterSizes(kN, 100, 0.1);
  const std::vector<int64_t> strides = AllanStrides(kN, sizes, 4);
  ASSERT_GE(strides.front(), 64);
  const IntegratedSignal signal(std::vector<double>(y), 200.0, "gyro x");
  const AllanCurve exact = signal.Deviation(sizes);
  const AllanCurve strided = signal.Deviation(sizes, strides);
  int outside_90 = 0;
  int strided_points = 0;
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (strides[i] == 1) continue;
    ++strided_points;
    // The noise is a mix of white FM and random-walk FM: the smaller of their EDFs.
    const double edf =
        std::min(StridedAllanEdf(PowerLawNoise::kWhiteFm, kN, sizes[i], strides[i]),
                 StridedAllanEdf(PowerLawNoise::kRandomWalkFm, kN, sizes[i], strides[i]));
    const DeviationInterval wide = AllanDeviationInterval(strided.adev[i], edf, 0.999);
    EXPECT_GE(exact.adev[i], wide.low) << "m = " << sizes[i] << ", stride " << strides[i];
    EXPECT_LE(exact.adev[i], wide.high) << "m = " << sizes[i] << ", stride " << strides[i];
    const DeviationInterval ninety = AllanDeviationInterval(strided.adev[i], edf, 0.9);
    if (exact.adev[i] < ninety.low || exact.adev[i] > ninety.high) ++outside_90;
  }
  ASSERT_GT(strided_points, 200);
  std::printf("%d of %d strided points outside their 90%% interval of the exact value\n",
              outside_90,
              strided_points);
  EXPECT_LE(outside_90, 0.15 * strided_points);
}

// Strides longer than the record (rows of the polyphase layout beyond S_N): one term each.
TEST(StridedAllanDeviation, StridesBeyondTheRecord) {
  const std::vector<double> y = GyroLikeAxis(100, 12);
  const IntegratedSignal signal(std::vector<double>(y), 200.0, "gyro x");
  const std::vector<int64_t> sizes = {1, 2, 7, 50};
  const std::vector<int64_t> strides = {256, 1, 128, 256};
  const AllanCurve curve = signal.Deviation(sizes, strides, 2);
  EXPECT_EQ(curve.num_terms, (std::vector<int64_t>{1, 97, 1, 1}));
  for (size_t i = 0; i < sizes.size(); ++i) {
    EXPECT_LE(RelativeDifference(curve.adev[i],
                                 std::sqrt(DirectStridedAllanVariance(y, sizes[i], strides[i]))),
              1e-12)
        << "m = " << sizes[i];
  }
}

TEST(StridedAllanDeviation, ErrorBarsFromTheTermsUsed) {
  const IntegratedSignal signal(AccelLikeAxis(1000, 11), 10.0, "accel x");
  const AllanCurve curve = signal.Deviation({1, 100, 2, 3}, {64, 64, 1, 4});
  // min(K = N / m, T): T = 16; K = 10; stride 1: K = 500; T = 249.
  EXPECT_DOUBLE_EQ(curve.adev_error[0], curve.adev[0] / std::sqrt(2.0 * 15));
  EXPECT_DOUBLE_EQ(curve.adev_error[1], curve.adev[1] / std::sqrt(2.0 * 9));
  EXPECT_DOUBLE_EQ(curve.adev_error[2], curve.adev[2] / std::sqrt(2.0 * 499));
  EXPECT_DOUBLE_EQ(curve.adev_error[3], curve.adev[3] / std::sqrt(2.0 * 248));
  EXPECT_EQ(curve.num_terms, (std::vector<int64_t>{16, 13, 997, 249}));
  using Sizes = std::vector<int64_t>;
  EXPECT_THROW(signal.Deviation(Sizes{1, 2}, Sizes{4, 3}), Error);  // 3 does not divide 4
  EXPECT_THROW(signal.Deviation(Sizes{1, 2}, Sizes{4}), Error);
  EXPECT_THROW(signal.Deviation(Sizes{501}, Sizes{2}), Error);
}

TEST(IntegratedSignal, RefusesBadSamples) {
  std::vector<double> with_nan = {1.0, 2.0, std::numeric_limits<double>::quiet_NaN(), 3.0};
  try {
    IntegratedSignal signal(std::move(with_nan), 100.0, "gyro y");
    FAIL() << "NaN accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("gyro y: sample 2 is not finite"));
  }
  try {
    IntegratedSignal signal(std::vector<double>(100, 0.25), 100.0, "accel x");
    FAIL() << "constant signal accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("accel x: all 100 samples are equal"));
  }
  EXPECT_THROW(IntegratedSignal(std::vector<double>{1.0}, 100.0, "x"), Error);
  EXPECT_THROW(IntegratedSignal(std::vector<double>{1.0, 2.0}, 0.0, "x"), Error);
  EXPECT_THROW(
      IntegratedSignal(std::vector<double>{1.0, 2.0}, std::numeric_limits<double>::infinity(), "x"),
      Error);
  const IntegratedSignal signal(std::vector<double>{1.0, 2.0, 4.0, 8.0, 16.0}, 10.0, "x");
  EXPECT_THROW(signal.AllanVariance(0), Error);
  EXPECT_THROW(signal.AllanVariance(3), Error);  // 2m > N
  EXPECT_NO_THROW(signal.AllanVariance(2));
  EXPECT_DOUBLE_EQ(signal.mean(), 31.0 / 5.0);
}

TEST(AllanClusterSizes, LogSpacedAndDeduplicated) {
  const std::vector<int64_t> sizes = AllanClusterSizes(1000000, 10, 0.1);
  const std::vector<int64_t> first = {
      1, 2, 3, 4, 5, 6, 8, 10, 13, 16, 20, 25, 32, 40, 50, 63, 79, 100};
  ASSERT_GT(sizes.size(), first.size());
  EXPECT_EQ(std::vector<int64_t>(sizes.begin(), sizes.begin() + first.size()), first);
  EXPECT_EQ(sizes.back(), 100000);
  for (size_t i = 1; i < sizes.size(); ++i) EXPECT_GT(sizes[i], sizes[i - 1]);
}

TEST(AllanClusterSizes, LimitsAndErrors) {
  EXPECT_EQ(AllanClusterSizes(1000, 1, 0.1), (std::vector<int64_t>{1, 10, 100}));
  EXPECT_EQ(AllanClusterSizes(1000, 1, 0.5), (std::vector<int64_t>{1, 10, 100}));
  EXPECT_EQ(AllanClusterSizes(2000, 1, 0.5), (std::vector<int64_t>{1, 10, 100, 1000}));
  EXPECT_TRUE(AllanClusterSizes(9, 10, 0.1).empty());
  EXPECT_THROW(AllanClusterSizes(1000, 0, 0.1), Error);
  EXPECT_THROW(AllanClusterSizes(1000, 10, 0.0), Error);
  EXPECT_THROW(AllanClusterSizes(1000, 10, 0.6), Error);
  EXPECT_THROW(AllanClusterSizes(1000, 10, std::numeric_limits<double>::quiet_NaN()), Error);
}

}  // namespace
}  // namespace splinecal
