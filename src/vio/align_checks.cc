#include "align_checks.h"

#include <cmath>
#include <string>

#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

std::string FormatVector(const Eigen::Vector3d& v) {
  return StringPrintf("%.3g,%.3g,%.3g", v.x(), v.y(), v.z());
}

}  // namespace

namespace internal {

bool CheckUncertainty(const AlignmentSolution& free,
                      const AlignmentSolution& refined,
                      const AlignmentSolution& with_bias,
                      const AlignOptions& options,
                      AlignResult* result) {
  const double s = refined.scale;
  const double relative_std = refined.scale_std / s;
  // What the bias-estimating solve says, for the messages: the user can pass that bias.
  const std::string bias_hint =
      with_bias.scale > 0.0
          ? StringPrintf("; with an estimated accelerometer bias (%s m/s^2) the free scale is "
                         "%.4g +- %.2g: pass a bias with --accel-bias X,Y,Z (that estimate, or "
                         "one from `splinecal fit` or `calibrate`)",
                         FormatVector(with_bias.accel_bias).c_str(),
                         with_bias.scale,
                         with_bias.scale_std)
          : std::string();
  // First: residuals larger than the assumed noise scale the standard deviation up (2), and the
  // scale is then "not determined" for a reason the message below names.
  if (!(refined.residual_noise_ratio <= options.max_residual_noise_ratio)) {
    result->message =
        StringPrintf(
            "the residuals are %.3g times the assumed noise (allowed %.3g): the camera poses "
            "and the IMU disagree beyond noise (an accelerometer bias, which is not modelled, "
            "--camera-position-std too small, a wrong T_cam_imu or time offset); scale %.4g",
            refined.residual_noise_ratio,
            options.max_residual_noise_ratio,
            s) +
        bias_hint;
    return false;
  }
  if (refined.residual_noise_ratio < options.min_residual_noise_ratio) {
    result->warnings.push_back(StringPrintf(
        "the residuals are %.3g times the assumed noise: the camera poses (or the IMU) are more "
        "accurate than --camera-position-std and --camera-rotation-std (or the IMU densities) "
        "say, so the IMU is under-weighted and the scale's standard deviation does not describe "
        "its error: pass the poses' own noise",
        refined.residual_noise_ratio));
  }
  if (!(relative_std <= options.max_scale_relative_std)) {
    result->message = StringPrintf(
        "the scale is not determined: %.4g with a standard deviation of %.3g (%.3g%%, allowed "
        "%.3g%%); the motion does not excite it enough (longer windows with changes of "
        "acceleration help)",
        s,
        refined.scale_std,
        100.0 * relative_std,
        100.0 * options.max_scale_relative_std);
    return false;
  }
  // The bias check: imposing the known norm moves an unmodelled accelerometer bias along
  // gravity into the scale (docs/align.md, "Limits"), so the refined scale departs from the
  // free one. The two variances are added (conservative: the estimates share data, so the
  // difference's variance is smaller); a shift within max_scale_relative_std only warns.
  const double shift = s - free.scale;
  const double shift_std = std::hypot(refined.scale_std, free.scale_std);
  if (std::abs(shift) <= options.max_accel_bias_scale_shift_sigmas * shift_std) return true;
  const std::string what = StringPrintf(
      "imposing the known gravity norm moves the scale from %.4g +- %.2g (free gravity, norm "
      "%.4g m/s^2) to %.4g +- %.2g (%.3g standard deviations, %.3g%%): an accelerometer bias "
      "along gravity, which is not modelled, goes into the scale",
      free.scale,
      free.scale_std,
      free.gravity_c0.norm(),
      s,
      refined.scale_std,
      std::abs(shift) / shift_std,
      100.0 * std::abs(shift) / s);
  if (std::abs(shift) / s > options.max_scale_relative_std) {
    result->message = "the scale is biased: " + what + bias_hint;
    return false;
  }
  result->warnings.push_back(what);
  return true;
}


}  // namespace internal
}  // namespace splinecal
