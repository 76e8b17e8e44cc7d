#include "splinecal/allan/work_budget.h"

#include <glog/logging.h>

#include <algorithm>
#include <string>

#include "splinecal/error.h"

namespace splinecal {
namespace {

// The smallest power of two >= x (x >= 1).
int64_t PowerOfTwoAtLeast(int64_t x) {
  int64_t p = 1;
  while (p < x) p *= 2;
  return p;
}

// s_m under the cap t_max (allan/work_budget.h).
int64_t StrideUnderCap(int64_t terms, int64_t t_max) {
  if (terms <= t_max) return 1;
  return PowerOfTwoAtLeast((terms + t_max - 1) / t_max);
}

}  // namespace

int64_t AllanTermCount(int64_t num_samples, int64_t m, int64_t stride) {
  CHECK_GE(m, 1);
  CHECK_LE(2 * m, num_samples);
  CHECK_GE(stride, 1);
  return (num_samples - 2 * m) / stride + 1;
}

std::vector<int64_t> AllanStrides(int64_t num_samples,
                                  const std::vector<int64_t>& cluster_sizes,
                                  int max_passes) {
  if (max_passes < 0) {
    throw Error("max passes must be 0 (no budget) or positive, got " + std::to_string(max_passes));
  }
  std::vector<int64_t> strides(cluster_sizes.size(), 1);
  if (max_passes == 0 || cluster_sizes.empty()) return strides;
  // The budget in terms; N * max_passes stays far below 2^63 for any record that fits in memory.
  const int64_t budget = num_samples * static_cast<int64_t>(max_passes);
  std::vector<int64_t> terms;
  int64_t total = 0;
  int64_t largest = 0;
  for (const int64_t m : cluster_sizes) {
    terms.push_back(AllanTermCount(num_samples, m, 1));
    total += terms.back();
    largest = std::max(largest, terms.back());
  }
  if (total <= budget) return strides;
  // sum_m T_used(m) does not decrease as t_max grows (each stride can only shrink): bisect for
  // the largest t_max within the budget. t_max = 1 always fits: one term per size, and there
  // are at most N / 2 sizes.
  auto used = [&](int64_t t_max) {
    int64_t sum = 0;
    for (size_t i = 0; i < terms.size(); ++i) {
      sum += AllanTermCount(num_samples, cluster_sizes[i], StrideUnderCap(terms[i], t_max));
    }
    return sum;
  };
  int64_t fits = 1;
  int64_t exceeds = largest;  // used(largest) = total > budget
  while (exceeds - fits > 1) {
    const int64_t middle = fits + (exceeds - fits) / 2;
    (used(middle) <= budget ? fits : exceeds) = middle;
  }
  for (size_t i = 0; i < terms.size(); ++i) strides[i] = StrideUnderCap(terms[i], fits);
  return strides;
}

}  // namespace splinecal
