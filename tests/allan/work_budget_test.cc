#include "splinecal/allan/work_budget.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

#include "splinecal/allan/allan_deviation.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

int64_t TermsUsed(int64_t n,
                  const std::vector<int64_t>& sizes,
                  const std::vector<int64_t>& strides) {
  int64_t total = 0;
  for (size_t i = 0; i < sizes.size(); ++i) total += AllanTermCount(n, sizes[i], strides[i]);
  return total;
}

bool IsPowerOfTwo(int64_t s) { return s >= 1 && (s & (s - 1)) == 0; }

TEST(AllanTermCount, CountsTheStridedStartIndices) {
  for (const int64_t n : {10, 11, 1000, 1001}) {
    for (int64_t m = 1; 2 * m <= n; m += 3) {
      for (const int64_t stride : {1, 2, 3, 8, 64, 5000}) {
        int64_t count = 0;
        for (int64_t k = 0; k <= n - 2 * m; k += stride) ++count;
        EXPECT_EQ(AllanTermCount(n, m, stride), count) << n << " " << m << " " << stride;
      }
    }
  }
}

// The default budget never strides 10 averaging times per decade (up to a tenth of the record)
// below 10^11 samples (work_budget.h): 57 passes on 10^7 samples, 98 on 10^11.
TEST(AllanStrides, TenPerDecadeStaysFullyOverlapping) {
  for (int64_t n = 1000; n <= 100'000'000'000; n *= 10) {
    const std::vector<int64_t> sizes = AllanClusterSizes(n, 10, 0.1);
    EXPECT_EQ(AllanStrides(n, sizes, kDefaultAllanMaxPasses), std::vector<int64_t>(sizes.size(), 1))
        << n;
  }
  const std::vector<int64_t> sizes = AllanClusterSizes(10'000'000, 10, 0.1);
  EXPECT_NEAR(
      TermsUsed(10'000'000, sizes, std::vector<int64_t>(sizes.size(), 1)) / 1e7, 57.03, 0.01);
}

TEST(AllanStrides, NoBudgetNeverStrides) {
  const std::vector<int64_t> sizes = AllanClusterSizes(1'000'000, 1000, 0.5);
  EXPECT_EQ(AllanStrides(1'000'000, sizes, 0), std::vector<int64_t>(sizes.size(), 1));
  EXPECT_THROW(AllanStrides(1000, {1, 2}, -1), Error);
}

// Above the budget: the terms used stay within max_passes * N, and the cap is raised until the
// budget is nearly spent: the next larger cap halves the strides of the averaging times at a
// power-of-two boundary, so what is left is about T_max terms per such time. Measured: at least
// 98.5% of the budget spent at 10 and 100 passes; at 1 pass and 1000 per decade on 2 * 10^4
// samples 89% (about 15 terms per averaging time, each rounded to whole terms and strides).
// Strides are powers of two and the shortest averaging times take the largest.
TEST(AllanStrides, BudgetRespectedAndNearlySpent) {
  for (const int64_t n : {20'000, 400'000, 10'000'000}) {
    for (const int per_decade : {30, 100, 1000}) {
      for (const int passes : {1, 10, 100}) {
        const std::vector<int64_t> sizes = AllanClusterSizes(n, per_decade, 0.1);
        const std::vector<int64_t> strides = AllanStrides(n, sizes, passes);
        const int64_t budget = n * passes;
        const int64_t used = TermsUsed(n, sizes, strides);
        const int64_t all = TermsUsed(n, sizes, std::vector<int64_t>(sizes.size(), 1));
        SCOPED_TRACE(testing::Message() << "N " << n << ", " << per_decade << " per decade, "
                                        << passes << " passes: used " << used << " of " << budget);
        EXPECT_LE(used, budget);
        if (all <= budget) {
          EXPECT_EQ(used, all);
          continue;
        }
        EXPECT_GE(used, (passes >= 10 ? 0.98 : 0.85) * budget);
        for (size_t i = 0; i < sizes.size(); ++i) {
          EXPECT_TRUE(IsPowerOfTwo(strides[i])) << strides[i];
          if (i > 0) {
            EXPECT_LE(strides[i], strides[i - 1]) << "m " << sizes[i];
          }
        }
      }
    }
  }
}

// A long averaging time with few terms keeps them all while the short ones are strided.
TEST(AllanStrides, FewTermsAreNotStrided) {
  constexpr int64_t kN = 100'000;
  const std::vector<int64_t> sizes = {1, 2, 3, 4, 5, 49'000, 50'000};
  const std::vector<int64_t> strides = AllanStrides(kN, sizes, 2);
  EXPECT_LE(TermsUsed(kN, sizes, strides), 2 * kN);
  EXPECT_EQ(strides[5], 1);  // 2001 terms
  EXPECT_EQ(strides[6], 1);  // 1 term
  EXPECT_GE(strides[0], 4);
}

}  // namespace
}  // namespace splinecal
