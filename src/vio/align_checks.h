// Step 5 of `Align` (vio/align.h, AlignOptions): the checks on the solved scale's uncertainty,
// private to src/vio/. They refuse a scale whose residuals are far beyond the assumed noise, that
// the motion does not determine, or that an unmodelled accelerometer bias has moved; they warn
// for residuals far below the assumed noise and for a smaller bias.
#ifndef SPLINECAL_SRC_VIO_ALIGN_CHECKS_H_
#define SPLINECAL_SRC_VIO_ALIGN_CHECKS_H_

#include "splinecal/vio/align.h"

namespace splinecal {
namespace internal {

// Returns false with result->message set when the refined scale is refused; appends to
// result->warnings otherwise. `free` and `with_bias` are the free-gravity solves without and with
// the accelerometer bias as unknowns (the messages name the latter's bias).
bool CheckUncertainty(const AlignmentSolution& free,
                      const AlignmentSolution& refined,
                      const AlignmentSolution& with_bias,
                      const AlignOptions& options,
                      AlignResult* result);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_VIO_ALIGN_CHECKS_H_
