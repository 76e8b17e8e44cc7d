// The kernels of second_differences.h. Moved here unchanged from allan_deviation.cc (the
// strided sums use them too): the overlapping curve keeps its bits.
#include "second_differences.h"

namespace splinecal {
namespace internal {
namespace {

// The kernel: squared second differences of the stored sums a (sums_ of IntegratedSignal),
//   sum_{j in block} (a[j + 2m] - 2 a[j + m] + a[j])^2,
// summed over blocks of at most kMaxKernelLength terms in double, in kLanes interleaved
// accumulators (independent add chains the compiler keeps in vector registers, so the loop is
// limited by loads, not by the latency of one accumulator). The terms are >= 0, so a block's
// relative rounding error is below (kMaxKernelLength / kLanes + kLanes) * 2^-53 ~ 6e-14; block sums
// are added in long double. The lanes make the result independent of the vector width, so every
// clone below computes the same bits (ISO C++ mode: no contraction into FMA). Eight lanes: four
// cluster sizes at once (see BlockSums4) then need 32 accumulators, which AVX2's 16 registers still
// hold as 8 vectors.
constexpr int kLanes = 8;

}  // namespace

#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
// One portable build, code paths chosen when the program loads (GCC function multi-versioning):
// AVX-512 or AVX2 where the CPU has them, SSE2 otherwise. Same results (see kLanes).
#define SPLINECAL_ALLAN_CLONES \
  __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default")))
#else
#define SPLINECAL_ALLAN_CLONES
#endif

SPLINECAL_ALLAN_CLONES
double BlockSum(const double* a0, const double* a1, const double* a2, int64_t length) {
  double acc[kLanes] = {};
  int64_t j = 0;
  for (; j + kLanes <= length; j += kLanes) {
    for (int lane = 0; lane < kLanes; ++lane) {
      const double d = a2[j + lane] - 2.0 * a1[j + lane] + a0[j + lane];
      acc[lane] += d * d;
    }
  }
  for (; j < length; ++j) {
    const double d = a2[j] - 2.0 * a1[j] + a0[j];
    acc[j % kLanes] += d * d;
  }
  // Pairwise reduction of the lanes.
  for (int width = kLanes / 2; width >= 1; width /= 2) {
    for (int lane = 0; lane < width; ++lane) acc[lane] += acc[lane + width];
  }
  return acc[0];
}

// BlockSum for four cluster sizes m_g over the same start indices: a0 = a + j is loaded once for
// all four (9 loads per 4 terms instead of 12; 30% less time in the single sweep of
// allan_deviation.cc). Each
// m's lanes add their terms in the same order as BlockSum, so both give the same bits.
SPLINECAL_ALLAN_CLONES
void BlockSums4(const double* a0,
                const double* const* a1,
                const double* const* a2,
                int64_t length,
                double* sums) {
  double acc[4][kLanes] = {};
  const double* const b0 = a1[0];
  const double* const b1 = a1[1];
  const double* const b2 = a1[2];
  const double* const b3 = a1[3];
  const double* const c0 = a2[0];
  const double* const c1 = a2[1];
  const double* const c2 = a2[2];
  const double* const c3 = a2[3];
  int64_t j = 0;
  for (; j + kLanes <= length; j += kLanes) {
    for (int lane = 0; lane < kLanes; ++lane) {
      const int64_t k = j + lane;
      const double x = a0[k];
      const double d0 = c0[k] - 2.0 * b0[k] + x;
      const double d1 = c1[k] - 2.0 * b1[k] + x;
      const double d2 = c2[k] - 2.0 * b2[k] + x;
      const double d3 = c3[k] - 2.0 * b3[k] + x;
      acc[0][lane] += d0 * d0;
      acc[1][lane] += d1 * d1;
      acc[2][lane] += d2 * d2;
      acc[3][lane] += d3 * d3;
    }
  }
  for (; j < length; ++j) {
    for (int g = 0; g < 4; ++g) {
      const double d = a2[g][j] - 2.0 * a1[g][j] + a0[j];
      acc[g][j % kLanes] += d * d;
    }
  }
  for (int g = 0; g < 4; ++g) {
    for (int width = kLanes / 2; width >= 1; width /= 2) {
      for (int lane = 0; lane < width; ++lane) acc[g][lane] += acc[g][lane + width];
    }
    sums[g] = acc[g][0];
  }
}

}  // namespace internal
}  // namespace splinecal
