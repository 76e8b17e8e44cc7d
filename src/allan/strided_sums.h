// The strided sums of the Allan deviation under a work budget (allan/work_budget.h), internal to
// allan/: for each cluster size m_i and stride s_i,
//
//     sum_{k = 0, s_i, 2 s_i, ... <= N - 2 m_i} (S_{k + 2 m_i} - 2 S_{k + m_i} + S_k)^2,
//
// S_0 = 0 and S_k = sums[k - 1] for k = 1 .. N (IntegratedSignal's storage).
//
// Evaluated on a polyphase copy of S: with P the largest stride, row r holds S_r, S_{r+P},
// S_{r+2P}, ... A start index k = c P + r is column c of row r, and S_{k+m} is column
// c + (r + m) / P of row (r + m) mod P, so for a fixed start row the three values of consecutive
// terms are three contiguous runs: the kernels of second_differences.h, as in the overlapping
// sweep. Stride s_i (dividing P) takes the start rows 0, s_i, 2 s_i, ... The copy is swept in
// blocks of columns whose window (all rows, the columns of the block plus 2 max(m) / P) stays in
// the cache while every cluster size uses it, like the overlapping near sweep.
#ifndef SPLINECAL_SRC_ALLAN_STRIDED_SUMS_H_
#define SPLINECAL_SRC_ALLAN_STRIDED_SUMS_H_

#include <cstdint>
#include <vector>

namespace splinecal {
namespace internal {

// The sums above (the terms of each block added in double, at most kMaxKernelLength of them, the
// blocks in long double), on up to num_threads threads; the result does not depend on
// num_threads. Requires 1 <= m_i <= N / 2, strides >= 1, each dividing the largest. The calling
// thread's window lives in *scratch when it is given (grown as needed, kept for the next call:
// pages written once are cheap to write again), else in memory of its own.
std::vector<long double> StridedSecondDifferenceSums(const double* sums,
                                                     int64_t num_samples,
                                                     const std::vector<int64_t>& cluster_sizes,
                                                     const std::vector<int64_t>& strides,
                                                     int num_threads,
                                                     std::vector<double>* scratch = nullptr);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_ALLAN_STRIDED_SUMS_H_
