#include "splinecal/allan/allan_deviation.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <limits>
#include <string>
#include <thread>
#include <utility>

#include "second_differences.h"
#include "splinecal/allan/work_budget.h"
#include "splinecal/error.h"
#include "strided_sums.h"

namespace splinecal {
namespace {

using internal::BlockSum;
using internal::BlockSums4;

// Start indices per block of the near sweep: at most internal::kMaxKernelLength per kernel call
// (second_differences.h).
constexpr int64_t kBlock = internal::kMaxKernelLength;

// Memory traffic, not arithmetic, limits a pass over 10^7 samples, so the passes are organised
// around the cache (a 10^7-sample axis is 80 MB):
//  - "near" cluster sizes (2m <= kNearSpan) are processed together, block by block: all of them
//    read a[j .. j + kBlock + 2m), a window that moves forward through the array and stays in the
//    last-level cache (16 MB at most) while every near m is summed, so the data comes from memory
//    once for all of them. Before d535ace the window was the L2 cache (1 MB, 2m <= 131072) and the
//    longer averaging times took the comb below: one pass from memory each, 20% more time at 10
//    averaging times per decade on 10^7 samples;
//  - "far" cluster sizes (records above 2 * 10^7 samples) are traversed as a comb: for a chunk of
//    start indices [r, r + kChunk), the chunks at r, r + m, r + 2m, r + 3m, ... in turn; the
//    second difference at chunk i reads chunks i, i + 1, i + 2, so each chunk comes from memory
//    once and is reused twice from cache.
constexpr int64_t kNearSpan = int64_t{1} << 21;
constexpr int64_t kChunk = 8192;

// sum_{j=0}^{count-1} (a[j + 2m] - 2 a[j + m] + a[j])^2 for one far m (comb traversal).
long double FarSum(const double* a, int64_t m, int64_t count) {
  long double total = 0.0L;
  for (int64_t r = 0; r < std::min(m, count); r += kChunk) {
    const int64_t width = std::min(kChunk, m - r);
    for (int64_t base = r; base < count; base += m) {
      const int64_t length = std::min(width, count - base);
      total += BlockSum(a + base, a + base + m, a + base + 2 * m, length);
    }
  }
  return total;
}

// The same sums for several near m at once, over the start indices j in [j_begin, j_end) (block
// by block), added to totals[i]. Four sizes at a time where all four have the whole block; the
// rest one by one.
void NearSums(const double* a,
              int64_t n,
              const std::vector<int64_t>& sizes,
              int64_t j_begin,
              int64_t j_end,
              long double* totals) {
  for (int64_t begin = j_begin; begin < j_end; begin += kBlock) {
    const int64_t block_end = std::min(j_end, begin + kBlock);
    // The largest m with every start index of this block (2m <= n - block_end).
    const int64_t whole_block = (n - block_end) / 2;
    size_t i = 0;
    for (; i + 4 <= sizes.size() &&
           std::max({sizes[i], sizes[i + 1], sizes[i + 2], sizes[i + 3]}) <= whole_block;
         i += 4) {
      const double* middle[4];
      const double* last[4];
      for (int g = 0; g < 4; ++g) {
        middle[g] = a + begin + sizes[i + g];
        last[g] = a + begin + 2 * sizes[i + g];
      }
      double sums[4];
      BlockSums4(a + begin, middle, last, block_end - begin, sums);
      for (int g = 0; g < 4; ++g) totals[i + g] += sums[g];
    }
    for (; i < sizes.size(); ++i) {
      const int64_t m = sizes[i];
      const int64_t count = std::min(block_end, n - 2 * m);
      if (begin >= count) continue;
      totals[i] += BlockSum(a + begin, a + begin + m, a + begin + 2 * m, count - begin);
    }
  }
}

// Near sums are computed per segment of start indices and the segment totals added in order, so
// that the result does not depend on how many threads share the segments.
constexpr int64_t kSegment = 256 * kBlock;

}  // namespace

std::vector<int64_t> AllanClusterSizes(int64_t num_samples,
                                       int taus_per_decade,
                                       double max_tau_fraction) {
  if (taus_per_decade < 1 || taus_per_decade > 1000) {
    throw Error("taus per decade must be in [1, 1000], got " + std::to_string(taus_per_decade));
  }
  if (!(max_tau_fraction > 0.0 && max_tau_fraction <= 0.5)) {
    throw Error("max tau fraction must be in (0, 0.5], got " + std::to_string(max_tau_fraction));
  }
  // K = N / m >= 2 independent clusters at the longest averaging time.
  const int64_t largest = std::min<int64_t>(
      static_cast<int64_t>(std::floor(max_tau_fraction * static_cast<double>(num_samples))),
      num_samples / 2);
  std::vector<int64_t> sizes;
  for (int j = 0;; ++j) {
    const double exact = std::pow(10.0, static_cast<double>(j) / taus_per_decade);
    const int64_t m = std::llround(exact);
    if (m > largest) break;
    if (sizes.empty() || m != sizes.back()) sizes.push_back(m);
  }
  return sizes;
}

double AllanRelativeError(int64_t num_samples, int64_t m) {
  const int64_t clusters = num_samples / m;
  if (clusters < 2) return std::numeric_limits<double>::infinity();
  return 1.0 / std::sqrt(2.0 * static_cast<double>(clusters - 1));
}

double AllanRelativeError(int64_t num_samples, int64_t m, int64_t stride) {
  if (stride == 1) return AllanRelativeError(num_samples, m);
  // A strided estimate has at most as many independent terms as it has terms (allan/edf.h).
  const int64_t clusters = std::min(num_samples / m, AllanTermCount(num_samples, m, stride));
  if (clusters < 2) return std::numeric_limits<double>::infinity();
  return 1.0 / std::sqrt(2.0 * static_cast<double>(clusters - 1));
}

IntegratedSignal::IntegratedSignal(std::vector<double>&& samples,
                                   double rate_hz,
                                   const std::string& name)
    : sums_(std::move(samples)), rate_hz_(rate_hz), mean_(0.0) {
  if (!(std::isfinite(rate_hz) && rate_hz > 0.0)) {
    throw Error(name + ": sample rate must be positive and finite, got " + std::to_string(rate_hz));
  }
  const int64_t n = static_cast<int64_t>(sums_.size());
  if (n < 2) throw Error(name + ": needs at least 2 samples, got " + std::to_string(n));
  // Any constant c gives the same Allan variance; the mean only keeps the sums small, so it is
  // taken in double (four interleaved sums), fast and accurate enough for that.
  double partial[4] = {0.0, 0.0, 0.0, 0.0};
  bool finite = true;
  bool constant = true;
  const double first = sums_[0];
  for (int64_t i = 0; i < n; ++i) {
    const double y = sums_[i];
    finite = finite && std::isfinite(y);
    constant = constant && y == first;
    partial[i & 3] += y;
  }
  if (!finite) {
    for (int64_t i = 0; i < n; ++i) {
      if (!std::isfinite(sums_[i])) {
        throw Error(name + ": sample " + std::to_string(i) + " is not finite");
      }
    }
  }
  const long double sum =
      static_cast<long double>((partial[0] + partial[1]) + (partial[2] + partial[3]));
  if (constant) {
    throw Error(name + ": all " + std::to_string(n) + " samples are equal (" +
                std::to_string(sums_[0]) + "): a constant signal has no noise to identify");
  }
  const long double mean = sum / static_cast<long double>(n);
  mean_ = static_cast<double>(mean);
  // In place: sums_[k - 1] = sum_{i<k} (y_i - mean). Element k - 1 is read before it is written.
  long double running = 0.0L;
  for (int64_t i = 0; i < n; ++i) {
    running += static_cast<long double>(sums_[i]) - mean;
    sums_[i] = static_cast<double>(running);
  }
}

void IntegratedSignal::CheckClusterSize(int64_t m) const {
  const int64_t n = num_samples();
  if (m < 1 || 2 * m > n) {
    throw Error("cluster size " + std::to_string(m) +
                " outside [1, N/2] for N = " + std::to_string(n) + " samples");
  }
}

double IntegratedSignal::AllanVariance(int64_t m) const {
  // With S_k = sum_{i<k} (y_i - mean) and theta_k = tau_0 S_k, tau = m tau_0:
  // AVAR = sum_{k=0}^{N-2m} (S_{k+2m} - 2 S_{k+m} + S_k)^2 / (2 m^2 (N - 2m + 1)).
  // S_0 = 0 is not stored (sums_[k - 1] = S_k): the k = 0 term first, then k = 1 .. N - 2m.
  // The k >= 1 terms are the kernel's j = k - 1.
  return Variances({m}, 1)[0];
}

double IntegratedSignal::Normalise(int64_t m, long double sum_of_k_at_least_1) const {
  const int64_t n = num_samples();
  const double* s = sums_.data();
  const double first = s[2 * m - 1] - 2.0 * s[m - 1];
  const long double total = static_cast<long double>(first) * first + sum_of_k_at_least_1;
  const long double terms = static_cast<long double>(n - 2 * m + 1);
  const long double m_ld = static_cast<long double>(m);
  return static_cast<double>(total / (2.0L * m_ld * m_ld * terms));
}

std::vector<double> IntegratedSignal::Variances(const std::vector<int64_t>& cluster_sizes,
                                                int num_threads) const {
  const int64_t n = num_samples();
  const double* a = sums_.data();
  std::vector<int64_t> near;
  std::vector<size_t> far;  // indices into cluster_sizes
  int64_t longest = 0;      // start indices the near sizes need
  for (size_t i = 0; i < cluster_sizes.size(); ++i) {
    const int64_t m = cluster_sizes[i];
    CheckClusterSize(m);
    if (2 * m <= kNearSpan) {
      near.push_back(m);
      longest = std::max(longest, n - 2 * m);
    } else {
      far.push_back(i);
    }
  }
  // Tasks: each far size (one comb pass), then each segment of the near sweep; long tasks first.
  const int64_t num_segments = near.empty() ? 0 : (longest + kSegment - 1) / kSegment;
  const int64_t num_tasks = static_cast<int64_t>(far.size()) + num_segments;
  std::vector<long double> far_totals(far.size(), 0.0L);
  std::vector<long double> segment_totals(num_segments * near.size(), 0.0L);
  std::atomic<int64_t> next{0};
  auto work = [&]() {
    for (int64_t task = next++; task < num_tasks; task = next++) {
      if (task < static_cast<int64_t>(far.size())) {
        const int64_t m = cluster_sizes[far[task]];
        far_totals[task] = FarSum(a, m, n - 2 * m);
      } else {
        const int64_t segment = task - static_cast<int64_t>(far.size());
        const int64_t begin = segment * kSegment;
        NearSums(a,
                 n,
                 near,
                 begin,
                 std::min(longest, begin + kSegment),
                 &segment_totals[segment * near.size()]);
      }
    }
  };
  const int threads =
      static_cast<int>(std::clamp<int64_t>(num_threads, 1, std::max<int64_t>(num_tasks, 1)));
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) pool.emplace_back(work);
  work();
  for (std::thread& thread : pool) thread.join();

  std::vector<double> variances(cluster_sizes.size());
  size_t next_near = 0;
  size_t next_far = 0;
  for (size_t i = 0; i < cluster_sizes.size(); ++i) {
    const int64_t m = cluster_sizes[i];
    long double rest = 0.0L;
    if (2 * m <= kNearSpan) {
      for (int64_t segment = 0; segment < num_segments; ++segment) {
        rest += segment_totals[segment * near.size() + next_near];
      }
      ++next_near;
    } else {
      rest = far_totals[next_far++];
    }
    variances[i] = Normalise(m, rest);
  }
  return variances;
}

AllanCurve IntegratedSignal::Deviation(const std::vector<int64_t>& cluster_sizes,
                                       int num_threads) const {
  return Deviation(cluster_sizes, std::vector<int64_t>(cluster_sizes.size(), 1), num_threads);
}

AllanCurve IntegratedSignal::Deviation(const std::vector<int64_t>& cluster_sizes,
                                       const std::vector<int64_t>& strides,
                                       int num_threads,
                                       std::vector<double>* scratch) const {
  if (strides.size() != cluster_sizes.size()) {
    throw Error("got " + std::to_string(strides.size()) + " strides for " +
                std::to_string(cluster_sizes.size()) + " cluster sizes");
  }
  const int64_t n = num_samples();
  const int64_t largest_stride =
      strides.empty() ? 1 : *std::max_element(strides.begin(), strides.end());
  for (size_t i = 0; i < cluster_sizes.size(); ++i) {
    CheckClusterSize(cluster_sizes[i]);
    if (strides[i] < 1 || largest_stride % strides[i] != 0) {
      throw Error("stride " + std::to_string(strides[i]) + " does not divide the largest, " +
                  std::to_string(largest_stride));
    }
  }
  AllanCurve curve;
  curve.rate_hz = rate_hz_;
  curve.num_samples = n;
  curve.cluster_sizes = cluster_sizes;
  curve.strides = strides;
  std::vector<double> variances;
  if (largest_stride == 1) {
    // The overlapping estimator: the near sweep and the comb.
    variances = Variances(cluster_sizes, num_threads);
  } else {
    const std::vector<long double> sums = internal::StridedSecondDifferenceSums(
        sums_.data(), n, cluster_sizes, strides, num_threads, scratch);
    for (size_t i = 0; i < cluster_sizes.size(); ++i) {
      const long double m = static_cast<long double>(cluster_sizes[i]);
      const long double terms =
          static_cast<long double>(AllanTermCount(n, cluster_sizes[i], strides[i]));
      variances.push_back(static_cast<double>(sums[i] / (2.0L * m * m * terms)));
    }
  }
  for (size_t i = 0; i < cluster_sizes.size(); ++i) {
    const int64_t m = cluster_sizes[i];
    const double adev = std::sqrt(variances[i]);
    curve.tau_s.push_back(static_cast<double>(m) / rate_hz_);
    curve.adev.push_back(adev);
    curve.adev_error.push_back(adev * AllanRelativeError(n, m, strides[i]));
    curve.num_terms.push_back(AllanTermCount(n, m, strides[i]));
  }
  return curve;
}

AllanCurve OverlappingAllanDeviation(const std::vector<double>& samples,
                                     double rate_hz,
                                     const std::vector<int64_t>& cluster_sizes,
                                     const std::string& name) {
  std::vector<double> copy = samples;
  return IntegratedSignal(std::move(copy), rate_hz, name).Deviation(cluster_sizes);
}

}  // namespace splinecal
