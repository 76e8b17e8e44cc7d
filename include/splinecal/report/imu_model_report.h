// The estimated IMU model (calibrate --imu-model; docs/imu_models.md) as report.html and the
// printed summary show it, beside T_cam_imu: each matrix row by row with each entry's standard
// deviation, C_gyro_i as its rotation vector [deg], the size effect's lever arms [mm]. An entry
// that is not a parameter (M's upper triangle) shows no std; a parameter without one (held at
// nominal because the recording does not determine it, or no covariance) says so.
#ifndef SPLINECAL_REPORT_IMU_MODEL_REPORT_H_
#define SPLINECAL_REPORT_IMU_MODEL_REPORT_H_

#include <string>

#include "splinecal/calib/calibrate.h"

namespace splinecal {

// Lines of the summary (empty for the `calibrated` model), e.g.
//   IMU model scale-misalignment (Kalibr's imu0; each entry: value (std))
//     M_a row 0: 1.000110 (0.002100), 0, 0
std::string ImuModelText(const CalibrationResult& result);

// report.html's "IMU model" section (empty for the `calibrated` model): a table, one row per
// matrix row, values and stds as the T_cam_imu rows show them.
std::string ImuModelHtml(const CalibrationResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_IMU_MODEL_REPORT_H_
