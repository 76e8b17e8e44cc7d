// The kernels of the Allan deviation passes, internal to allan/: sums of squared second
// differences over contiguous runs of the integrated signal. Shared by the overlapping sweep
// (allan_deviation.cc) and the strided one (strided_sums.cc), so that both add their terms in the
// same order with the same arithmetic.
#ifndef SPLINECAL_SRC_ALLAN_SECOND_DIFFERENCES_H_
#define SPLINECAL_SRC_ALLAN_SECOND_DIFFERENCES_H_

#include <cstdint>

namespace splinecal {
namespace internal {

// The longest run a caller passes in one call: the relative rounding error of a call's double
// sum stays below 6e-14 (second_differences.cc); callers add the calls' sums in long double.
constexpr int64_t kMaxKernelLength = 4096;

// sum_{j < length} (a2[j] - 2 a1[j] + a0[j])^2 in eight interleaved double accumulators, reduced
// pairwise: the same bits on every instruction set.
double BlockSum(const double* a0, const double* a1, const double* a2, int64_t length);

// BlockSum for four runs a1[g], a2[g] (g = 0 .. 3) that share a0, into sums[g]; the same bits as
// four BlockSum calls.
void BlockSums4(const double* a0,
                const double* const* a1,
                const double* const* a2,
                int64_t length,
                double* sums);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ALLAN_SECOND_DIFFERENCES_H_
