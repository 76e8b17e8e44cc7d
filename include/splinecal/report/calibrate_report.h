// What `splinecal calibrate` writes (docs/calibrate.md, "Outputs") besides camchain-imucam.yaml
// (io/camchain_yaml.h) and spline.csv (io/spline_csv.h), each as a string (the command stages
// them in an OutputDir and prints the summary):
//
//   result.yaml              cam0's estimates at the top level (T_cam_imu, timeshift_cam_imu,
//                            line_delay with their stds, reprojection RMS), the IMU biases,
//                            gravity, residual RMS, solver figures, every camera under `cameras`
//                            when there are several, and `warnings` in plain words.
//   reprojection_errors.csv  one row per used observation: #t_ns,cam_id,point_id,u,v,error_u,
//                            error_v (camera clock [ns], pixel and predicted - observed [px]).
//   report.html              the input files, the IMU noise model, a table of the estimates
//                            and SVG plots (plot/svg_plot.h): reprojection errors per camera
//                            (scatter, over time, against the image position), IMU residuals
//                            and biases over time, the trajectory.
//   summary                  the lines printed on stdout: each camera's T_cam_imu and stds,
//                            the residual RMS and the warnings.
#ifndef SPLINECAL_REPORT_CALIBRATE_REPORT_H_
#define SPLINECAL_REPORT_CALIBRATE_REPORT_H_

#include <string>

#include "splinecal/calib/calibrate.h"

namespace splinecal {

// The files calibrate read, listed in report.html (empty: not given).
struct CalibrateReportInputs {
  std::string imu_path;
  std::string observations_path;
  std::string camchain_path;
  std::string target_path;
  std::string initial_poses_path;
  std::string imu_yaml_path;  // empty: options.model.noise holds the ADIS16448 defaults
};

std::string CalibrateResultYaml(const CalibrationResult& result, const CalibrateOptions& options);
std::string CalibrateReprojectionCsv(const CalibrationResult& result);
// Plots show at most max_points points per series (evenly decimated); the noise model is
// options.model.noise.
std::string CalibrateReportHtml(const CalibrationResult& result,
                                const CalibrateOptions& options,
                                const CalibrateReportInputs& inputs,
                                int max_points = 6000);
std::string CalibrateSummaryText(const CalibrationResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_CALIBRATE_REPORT_H_
