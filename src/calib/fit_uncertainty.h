// What `fit` reports about its uncertainty (private to src/calib/): standard deviations from the
// covariance of the reported quantities, and plain-words warnings for what the data does not
// determine (FitOptions::excitation) or cannot tell apart.
#ifndef SPLINECAL_SRC_CALIB_FIT_UNCERTAINTY_H_
#define SPLINECAL_SRC_CALIB_FIT_UNCERTAINTY_H_

#include <Eigen/Core>

#include "splinecal/calib/fit.h"

namespace splinecal {

// C: the covariance of the reported quantities in FitResult::covariance_labels' order (gyro
// bias, accel bias, gravity direction, then time offset and extrinsic when estimated).
// result->gravity_w and covariance_labels must be set.
void ReportFitUncertainty(const FitOptions& options, const Eigen::MatrixXd& C, FitResult* result);

// No covariance: every standard deviation NaN and a warning that says why that happens.
void ReportSingularFitInformation(const FitOptions& options, FitResult* result);

}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_FIT_UNCERTAINTY_H_
