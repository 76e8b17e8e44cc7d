// `splinecal intrinsics --compare-models`: pinhole-radtan, pinhole-equi and ds-none fitted to the
// same corners, so the user sees when the chosen model is the wrong one (docs/intrinsics.md,
// "Choosing a model").
//
// The corners are the ones the main calibration used (after its outlier pass and with its views),
// and every model solves the exact least-squares problem over them (no loss, no outlier removal,
// no view set aside, the cameras sharing each instant's target pose as in the main solve): the
// sums of squares then compare, and a model whose sum is much larger misfits the lens. Its
// residual map (report.html) shows where. On EuRoC cam0 (every 8th frame) radtan's sum is 33% above
// pinhole-equi's and ds-none's (5762 against 4315 and 4323 px^2), its misfit in the image's corners
// (docs/intrinsics.md, "Choosing a model").
#ifndef SPLINECAL_INTRINSICS_COMPARE_MODELS_H_
#define SPLINECAL_INTRINSICS_COMPARE_MODELS_H_

#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"

namespace splinecal {

// The models compared, in this order.
inline constexpr const char* kComparedModels[] = {"pinhole-radtan", "pinhole-equi", "ds-none"};

// One model fitted to the corners: every camera's result and the corners' errors, or why it
// failed (a model that cannot start or converge on these corners).
struct ModelFit {
  std::string model;
  std::vector<IntrinsicsCameraResult> cameras;
  std::vector<ReprojectionSample> residuals;
  std::vector<double> sum_of_squares_px2;  // per camera
  std::string failure;  // empty: fitted
};

// Fits every model of kComparedModels to the corners `result` used, with the image sizes of
// `cameras` and the solver options of `options`. Never throws for a model that fails: its
// ModelFit says why.
std::vector<ModelFit> CompareModels(const IntrinsicsResult& result,
                                    const CalibrationTarget& target,
                                    const std::vector<IntrinsicsCameraSpec>& cameras,
                                    const IntrinsicsOptions& options);

// The comparison as a text table (camera, model, RMS, sum of squares, corners, parameters in
// Kalibr's names), for the command's summary.
std::string ModelComparisonText(const std::vector<ModelFit>& fits);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_COMPARE_MODELS_H_
