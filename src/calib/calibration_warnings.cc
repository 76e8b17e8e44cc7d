#include "calibration_warnings.h"

#include <array>
#include <cmath>
#include <string>

#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

namespace {

// A reported std this many times the noise model's is named in a warning.
constexpr double kWarnStdInflation = 2.0;

}  // namespace

void AddStandardDeviationWarnings(const CalibrateOptions& options,
                                  const ImuNoiseEstimate& noise,
                                  CalibrationResult* result) {
  if (result->std_inflation > kWarnStdInflation) {
    const std::array<double, kNumImuResidualKinds> ratio = noise.MeasuredOverGiven();
    result->warnings.push_back(
        "the data scatter more than the noise model explains: standard deviations are up to " +
        StringPrintf("%.2g", result->std_inflation) +
        "x the noise model's (IMU white noise measured at " + StringPrintf("%.2g", ratio[0]) +
        "x (gyro) and " + StringPrintf("%.2g", ratio[1]) +
        "x (accelerometer) the given densities; the cluster-robust scatter over " +
        std::to_string(result->robust_clusters) + " time windows" +
        (result->view_clusters > 0
             ? " and " + std::to_string(result->view_clusters) + " kinds of target view"
             : std::string()) +
        "): likely vibration above the spline's bandwidth, a knot spacing too "
        "coarse for the motion, or sensor errors the model lacks (docs/calibrate.md, \"How much "
        "to trust the numbers\")");
  }
  for (size_t c = 0; c < result->cameras.size(); ++c) {
    const CameraEstimate& estimate = result->cameras[c];
    const double line_delay = estimate.calibration.line_delay_s;
    const std::string name = "cam" + std::to_string(c);
    if (estimate.rotation_std_deg.maxCoeff() > options.warn_rotation_std_deg) {
      result->warnings.push_back(name +
                                 ": the rotation of T_cam_imu is poorly determined (std up to " +
                                 StringPrintf("%.3g", estimate.rotation_std_deg.maxCoeff()) +
                                 " deg): rotate the rig more, about all three axes");
    }
    if (estimate.translation_std_m.maxCoeff() > options.warn_translation_std_m) {
      result->warnings.push_back(
          name + ": the translation of T_cam_imu is poorly determined (std up to " +
          StringPrintf("%.3g", 1e3 * estimate.translation_std_m.maxCoeff()) +
          " mm): it shows only through rotational accelerations; rotate faster and longer");
    }
    if (options.estimate_time_offset &&
        estimate.time_offset_std_s > options.warn_time_offset_std_s) {
      result->warnings.push_back(name + ": the time offset is poorly determined (std " +
                                 StringPrintf("%.3g", 1e3 * estimate.time_offset_std_s) +
                                 " ms): the motion is too slow or too smooth");
    }
    if (options.rolling_shutter && line_delay > 0.0 &&
        estimate.line_delay_std_s > options.warn_line_delay_relative_std * line_delay &&
        line_delay > 3.0 * estimate.line_delay_std_s) {
      result->warnings.push_back(
          name + ": the line delay is poorly determined (std " +
          StringPrintf("%.3g", 100.0 * estimate.line_delay_std_s / line_delay) +
          "% of its value)");
    }
    if (std::abs(estimate.calibration.time_offset_s) > 0.99 * options.max_time_offset_s &&
        options.estimate_time_offset) {
      result->warnings.push_back(name + ": the time offset ended at its bound +-" +
                                 StringPrintf("%.3g", options.max_time_offset_s) + " s");
    }
  }
}

}  // namespace internal
}  // namespace splinecal
