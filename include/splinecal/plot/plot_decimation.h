// The one rule every splinecal plot uses to keep long series drawable: "at most N points per
// series". A report (report.html of `fit` and `calibrate`) or a picture (trajectory.svg of
// `integrate`) plots every k-th sample, with the smallest stride k that leaves at most N of them,
// so that the files stay a few MB however long the recording is.
#ifndef SPLINECAL_PLOT_PLOT_DECIMATION_H_
#define SPLINECAL_PLOT_PLOT_DECIMATION_H_

#include <cstddef>
#include <vector>

namespace splinecal {
namespace plot {

// The indices 0, k, 2k, ... below n, k = max(1, ceil(n / max_points)) (max_points < 1 counts as
// 1), so at most max_points of them. With keep_last, n - 1 is appended when the stride skips it
// (a line then ends where the data ends; at most max_points + 1 indices). Empty for n = 0.
std::vector<size_t> DecimatedIndices(size_t n, int max_points, bool keep_last);

}  // namespace plot
}  // namespace splinecal

#endif  // SPLINECAL_PLOT_PLOT_DECIMATION_H_
