// `splinecal evaluate` as a library call: a spline's pose, rates and predicted IMU reading at
// evenly spaced times (samples.csv) and optionally at a fixed step over its valid range
// (evaluation.csv), with result.yaml. The command line and the Python module both call it.
#ifndef SPLINECAL_REPORT_EVALUATE_REPORT_H_
#define SPLINECAL_REPORT_EVALUATE_REPORT_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/imu/imu_model.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {

// The spline and the IMU model at one time.
struct SplineEvaluation {
  int64_t t_ns = 0;
  SE3d T_w_s;
  Eigen::Vector3d w_s, v_w, a_w, gyro, accel;  // [rad/s], [m/s], [m/s^2], IMU reading
};

struct EvaluateOptions {
  int samples = 5;       // evenly spaced times, ends included, 2 to 100000
  double every_s = 0.0;  // evaluation.csv's step [s]; 0: no evaluation.csv
  double gravity_m_s2 = kDefaultGravity;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // b_g [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // b_a [m/s^2]
};

// Throws splinecal::Error (worded with the command's flags) for samples outside 2..100000, a
// negative or non-finite every_s, or an every_s that would write more than 1e8 rows.
void CheckEvaluateOptions(const SE3Splined& spline, const EvaluateOptions& options);

struct EvaluateRun {
  std::vector<SplineEvaluation> samples;  // at the evenly spaced times
  int64_t evaluation_rows = 0;            // rows of evaluation.csv (0 without every_s)
  std::vector<OutputFile> files;          // samples.csv, [evaluation.csv,] result.yaml
};

// Evaluates `spline` (read from spline_path, named in result.yaml) as `splinecal evaluate`.
EvaluateRun EvaluateSplineFiles(const SE3Splined& spline,
                                const std::string& spline_path,
                                const EvaluateOptions& options);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_EVALUATE_REPORT_H_
