// The work budget of the Allan deviation: how many second differences each averaging time may
// use, so that the time of `splinecal allan` hardly grows with the number of averaging times.
//
// The overlapping estimator (allan/allan_deviation.h) at cluster size m averages
//
//     T_m = N - 2m + 1
//
// squared second differences d_k = theta_{k+2m} - 2 theta_{k+m} + theta_k, one per start index
// k = 0 .. N - 2m. Exact arithmetic has no shortcut (each m is its own sum of ~N terms), so every
// averaging time costs a pass over the data: 58 passes at 10 per decade on 10^7 samples, about
// 3800 at 1000 per decade.
//
// The budget caps the terms evaluated per axis at max_passes * N:
//  - when sum_m T_m <= max_passes * N, every averaging time uses every start index (stride 1):
//    the overlapping estimator, computed by the same code as without a budget, bit for bit. At the
//    default 100 passes this holds at 10 averaging times per decade (cluster sizes up to a tenth of
//    the record) for every record below 10^11 samples: 8 sizes up to m = 10, then 10 per decade,
//    57 passes on 10^7 samples;
//  - above it, a cap T_max is chosen and each averaging time with T_m > T_max uses every s_m-th
//    start index, k = 0, s_m, 2 s_m, ... (the same second differences, evenly strided):
//
//        s_m = 2^ceil(log2(T_m / T_max)),   T_used(m) = floor((N - 2m) / s_m) + 1 <= T_max,
//        AVAR = sum_{k = 0, s_m, ...} d_k^2 / (2 m^2 T_used),
//
//    with T_max the largest integer for which sum_m T_used(m) <= max_passes * N. T_m falls with
//    m, so the short averaging times take the largest strides; there the overlapping estimator
//    has an enormous number of degrees of freedom (allan/edf.h, StridedAllanEdf: the EDF of a
//    strided averaging time is min(overlapping EDF, T_used)).
//
// Why powers of two and not s_m = ceil(T_m / T_max) itself: the strided sums are evaluated as
// contiguous vector passes over a polyphase copy of theta (row r holds theta_r, theta_{r+S},
// theta_{r+2S}, ... for the largest stride S). When every stride divides S, the start indices of
// any s_m are whole rows, and so are theta_{k+m} and theta_{k+2m} (other rows, shifted): the same
// SIMD kernels as the overlapping passes, one copy of the data. Strides 31 .. 38 (what ceil gives
// at 1000 per decade on 10^7 samples) would need one copy per stride or a gather per load, which
// reads three cache lines per term. T_max is then raised until the budget is spent, so rounding
// the strides costs no terms overall, only their spread over the averaging times.
#ifndef SPLINECAL_ALLAN_WORK_BUDGET_H_
#define SPLINECAL_ALLAN_WORK_BUDGET_H_

#include <cstdint>
#include <vector>

namespace splinecal {

// The default of AllanOptions::max_passes and `--max-passes`.
constexpr int kDefaultAllanMaxPasses = 100;

// The stride of each cluster size (1 <= m <= num_samples / 2, any order) under a budget of
// max_passes * num_samples terms; max_passes = 0 means no budget (all strides 1). Every stride is
// a power of two, so every stride divides the largest. Throws splinecal::Error when max_passes is
// negative.
std::vector<int64_t> AllanStrides(int64_t num_samples,
                                  const std::vector<int64_t>& cluster_sizes,
                                  int max_passes);

// The number of start indices k = 0, stride, 2 stride, ... <= num_samples - 2m:
// floor((N - 2m) / stride) + 1 (T_m = N - 2m + 1 for stride 1).
int64_t AllanTermCount(int64_t num_samples, int64_t m, int64_t stride);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_WORK_BUDGET_H_
