// What `splinecal fit` writes (docs/fit.md, "Outputs"): result.yaml, residuals.csv,
// pose_residuals.csv and report.html, each as a string (the command stages them in an OutputDir;
// spline.csv comes from io/spline_csv.h).
//
//   result.yaml         the estimates with a `_std` entry beside each, residual RMS against the
//                       noise the weights assumed, solver figures, knot spacing and how it was
//                       chosen, `not_determined` and `warnings` in plain words.
//   residuals.csv       one row per IMU sample (IMU clock):
//                       #t_ns, gyro residual xyz (fitted - measured) [rad/s], accel residual xyz
//                       [m/s^2], gyro measured xyz, gyro fitted xyz, accel measured xyz, accel
//                       fitted xyz, gyro bias xyz, accel bias xyz
//   pose_residuals.csv  one row per pose (pose clock): #t_ns, position error xyz [m] (world),
//                       rotation error xyz [rad] (Log(R_measured^T R_fitted))
//   report.html         the input files, the IMU noise model, the summary and SVG plots
//                       (plot/svg_plot.h): measured against fitted gyro and accelerometer,
//                       residuals over time, biases over time.
#ifndef SPLINECAL_REPORT_FIT_REPORT_H_
#define SPLINECAL_REPORT_FIT_REPORT_H_

#include <string>

#include "splinecal/calib/fit.h"
#include "splinecal/imu/noise.h"

namespace splinecal {

// Where the inputs came from (written into result.yaml and the report).
struct FitReportInputs {
  std::string imu_path;
  std::string poses_path;
  std::string imu_yaml_path;  // empty: the ADIS16448 defaults (the noise is FitResult::imu_noise)
};

std::string FitResultYaml(const FitResult& result, const FitReportInputs& inputs);
std::string FitResidualsCsv(const FitResult& result);
std::string FitPoseResidualsCsv(const FitResult& result);
// Plots show at most max_points points per series (evenly decimated).
std::string FitReportHtml(const FitResult& result,
                          const FitReportInputs& inputs,
                          int max_points = 3000);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_FIT_REPORT_H_
