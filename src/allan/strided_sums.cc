#include "strided_sums.h"

#include <glog/logging.h>

#include <algorithm>
#include <atomic>
#include <cstring>
#include <thread>
#include <vector>

#include "second_differences.h"

namespace splinecal {
namespace internal {
namespace {

// Start indices (rows times columns) of a block besides its 2 max(m) span: 1 MB, the L2 cache
// per core. Measured on 10^7 samples at 1000 per decade (stride 64): 0.20 s per axis, 0.21 s with
// half, 0.28 s with a quarter, 0.22 s with twice. Columns per block are kept in
// [kMinColumns, kMaxKernelLength]: long runs for the kernels, and their error bound
// (second_differences.h).
constexpr int64_t kBlockStarts = 131072;
constexpr int64_t kMinColumns = 256;
// Start indices per segment: the unit whose sums are added in a fixed order (results independent
// of the number of threads), as in the overlapping sweep.
constexpr int64_t kSegmentStarts = int64_t{1} << 20;

// Where S_{k + shift} of a start index k = c P + r lies: row (r + shift) mod P, column c plus
// `column`.
struct Offset {
  int64_t row;
  int64_t column;
};
Offset Shifted(int64_t r, int64_t shift, int64_t period) {
  const int64_t t = r + shift % period;
  return {t % period, shift / period + t / period};
}

// The columns of start row r whose start index is a term of m: c P + r <= N - 2m.
int64_t ValidColumns(int64_t num_samples, int64_t m, int64_t r, int64_t period) {
  const int64_t last = num_samples - 2 * m - r;
  return last < 0 ? 0 : last / period + 1;
}

// A window of columns of the polyphase layout (strided_sums.h), S_k at row k mod P, column k / P,
// that slides forward with the sweep. Not the whole copy: on this project's VM the first write
// to fresh memory costs about 4 ms per MB (the host backs the pages), 0.35 s for a copy of 10^7
// samples, more than the strided sums themselves. The window is span * 1.5 columns of every row
// (24 MB for 10^7 samples at a tenth of the record), in the caller's scratch vector when given,
// so that the next axis reuses pages already backed.
class PolyphaseWindow {
 public:
  // span: the most columns needed at once (a block plus the largest shift).
  // Uses *storage (grown when too small).
  PolyphaseWindow(const double* sums,
                  int64_t num_samples,
                  int64_t period,
                  int64_t span,
                  std::vector<double>* storage)
      : sums_(sums),
        num_samples_(num_samples),
        period_(period),
        columns_(num_samples / period + 1),
        width_(std::min(columns_, span + std::max(span / 2, kMinColumns))) {
    if (static_cast<int64_t>(storage->size()) < period * width_) storage->resize(period * width_);
    data_ = storage->data();
  }

  // Makes columns [c_begin, c_end) readable (c_begin never decreasing, c_end - c_begin <= span):
  // slides the window when it must, then copies in the columns not yet there.
  void Cover(int64_t c_begin, int64_t c_end) {
    c_end = std::min(c_end, columns_);
    CHECK_GE(c_begin, base_);
    CHECK_LE(c_end - c_begin, width_);
    if (filled_ < c_begin) filled_ = base_ = c_begin;  // a jump: nothing to keep
    if (c_end > base_ + width_) {
      const int64_t keep = filled_ - c_begin;
      for (int64_t r = 0; r < period_; ++r) {
        double* row = data_ + r * width_;
        std::memmove(row, row + (c_begin - base_), keep * sizeof(double));
      }
      base_ = c_begin;
    }
    // Tiles of kTile consecutive sums (32 KB, read once into L1) written as P runs of kTile / P
    // columns: whole cache lines of each row, a few pages at a time.
    constexpr int64_t kTile = 4096;
    const int64_t tile_columns = std::max<int64_t>(8, kTile / period_);
    for (int64_t c0 = filled_; c0 < c_end; c0 += tile_columns) {
      const int64_t c1 = std::min(c_end, c0 + tile_columns);
      for (int64_t r = 0; r < period_; ++r) {
        double* row = data_ + r * width_;
        // S_k = sums_[k - 1] for 1 <= k <= N; S_0 = 0, and 0 beyond S_N (rows r > N hold none).
        const int64_t first = std::min(c1, r == 0 ? std::max<int64_t>(c0, 1) : c0);
        const int64_t last = r > num_samples_
                                 ? first
                                 : std::max(first, std::min(c1, (num_samples_ - r) / period_ + 1));
        for (int64_t c = c0; c < first; ++c) row[c - base_] = 0.0;
        for (int64_t c = first; c < last; ++c) row[c - base_] = sums_[c * period_ + r - 1];
        for (int64_t c = last; c < c1; ++c) row[c - base_] = 0.0;
      }
    }
    filled_ = std::max(filled_, c_end);
  }

  // Column c of row r (covered).
  const double* At(int64_t r, int64_t c) const { return data_ + r * width_ + (c - base_); }

 private:
  const double* sums_;
  int64_t num_samples_;
  int64_t period_;
  int64_t columns_;  // of the whole layout: S_0 .. S_N
  int64_t width_;
  double* data_;        // row r at r * width_; written by Cover before it is read
  int64_t base_ = 0;    // the column at data_ offset 0 of each row
  int64_t filled_ = 0;  // columns [base_, filled_) hold data
};

}  // namespace

std::vector<long double> StridedSecondDifferenceSums(const double* sums,
                                                     int64_t num_samples,
                                                     const std::vector<int64_t>& cluster_sizes,
                                                     const std::vector<int64_t>& strides,
                                                     int num_threads,
                                                     std::vector<double>* scratch) {
  CHECK_EQ(cluster_sizes.size(), strides.size());
  const size_t num_sizes = cluster_sizes.size();
  if (num_sizes == 0) return {};
  const int64_t n = num_samples;
  const int64_t period = *std::max_element(strides.begin(), strides.end());
  int64_t smallest_m = n;
  int64_t largest_m = 0;
  for (size_t i = 0; i < num_sizes; ++i) {
    CHECK(cluster_sizes[i] >= 1 && 2 * cluster_sizes[i] <= n) << cluster_sizes[i];
    CHECK(strides[i] >= 1 && period % strides[i] == 0) << strides[i] << " " << period;
    smallest_m = std::min(smallest_m, cluster_sizes[i]);
    largest_m = std::max(largest_m, cluster_sizes[i]);
  }

  // Per start row, the terms of the sizes whose stride divides it, by increasing m (so that the
  // sizes that still have a whole block of columns come first), with where their S_{k+m} and
  // S_{k+2m} lie: computed once, not per block.
  struct RowTerm {
    size_t size;            // index into cluster_sizes
    Offset one;             // S_{k+m}
    Offset two;             // S_{k+2m}
    int64_t valid_columns;  // start columns c with c P + r <= N - 2m
  };
  std::vector<size_t> order(num_sizes);
  for (size_t i = 0; i < num_sizes; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return cluster_sizes[a] < cluster_sizes[b];
  });
  std::vector<std::vector<RowTerm>> rows(period);
  for (int64_t r = 0; r < period; ++r) {
    for (const size_t i : order) {
      if (r % strides[i] != 0) continue;
      const int64_t m = cluster_sizes[i];
      rows[r].push_back(
          {i, Shifted(r, m, period), Shifted(r, 2 * m, period), ValidColumns(n, m, r, period)});
    }
  }

  const int64_t block = std::clamp(kBlockStarts / period, kMinColumns, kMaxKernelLength);
  const int64_t segment = std::max<int64_t>(1, kSegmentStarts / (period * block)) * block;
  const int64_t used_columns = ValidColumns(n, smallest_m, 0, period);
  const int64_t num_segments = (used_columns + segment - 1) / segment;
  // The farthest column a block reads beyond its own: S_{k + 2 max(m)}.
  const int64_t reach = Shifted(period - 1, 2 * largest_m, period).column;
  std::vector<long double> segment_totals(num_segments * num_sizes, 0.0L);

  // Segments [first, last), in order, on one window.
  auto sweep = [&](int64_t first, int64_t last, std::vector<double>* storage) {
    if (first >= last) return;
    PolyphaseWindow window(sums, n, period, block + reach, storage);
    for (int64_t task = first; task < last; ++task) {
      long double* totals = &segment_totals[task * num_sizes];
      const int64_t c_end = std::min(used_columns, (task + 1) * segment);
      for (int64_t c0 = task * segment; c0 < c_end; c0 += block) {
        const int64_t c1 = std::min(c_end, c0 + block);
        window.Cover(c0, c1 + reach);
        for (int64_t r = 0; r < period; ++r) {
          const std::vector<RowTerm>& terms = rows[r];
          const double* a0 = window.At(r, c0);
          size_t g = 0;
          // Four sizes at a time while the fourth (largest m) still has every column.
          for (; g + 4 <= terms.size() && terms[g + 3].valid_columns >= c1; g += 4) {
            const double* middle[4];
            const double* end[4];
            for (int j = 0; j < 4; ++j) {
              const RowTerm& term = terms[g + j];
              middle[j] = window.At(term.one.row, c0 + term.one.column);
              end[j] = window.At(term.two.row, c0 + term.two.column);
            }
            double block_sums[4];
            BlockSums4(a0, middle, end, c1 - c0, block_sums);
            for (int j = 0; j < 4; ++j) totals[terms[g + j].size] += block_sums[j];
          }
          for (; g < terms.size(); ++g) {
            const RowTerm& term = terms[g];
            const int64_t valid_end = std::min(c1, term.valid_columns);
            if (valid_end <= c0) break;  // larger m have still fewer columns
            totals[term.size] += BlockSum(a0,
                                          window.At(term.one.row, c0 + term.one.column),
                                          window.At(term.two.row, c0 + term.two.column),
                                          valid_end - c0);
          }
        }
      }
    }
  };
  // Each thread takes a contiguous run of segments (one window slides through it); the segment
  // totals do not depend on which thread summed them.
  const int threads = static_cast<int>(std::clamp<int64_t>(num_threads, 1, num_segments));
  std::vector<std::vector<double>> storage(threads - 1);
  std::vector<std::thread> pool;
  for (int t = 1; t < threads; ++t) {
    pool.emplace_back(
        sweep, num_segments * t / threads, num_segments * (t + 1) / threads, &storage[t - 1]);
  }
  std::vector<double> own;
  sweep(0, num_segments / threads, scratch != nullptr ? scratch : &own);
  for (std::thread& thread : pool) thread.join();

  std::vector<long double> totals(num_sizes, 0.0L);
  for (int64_t s = 0; s < num_segments; ++s) {
    for (size_t i = 0; i < num_sizes; ++i) totals[i] += segment_totals[s * num_sizes + i];
  }
  return totals;
}

}  // namespace internal
}  // namespace splinecal
