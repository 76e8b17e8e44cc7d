// The files each command writes to --out, as a list (io/output_dir.h): the command line stages
// them in its OutputDir, and the Python module returns result.yaml's content from the same list
// (and writes the list with its `out=` keyword), so that both give the same files by
// construction. docs/<command>.md describes each file.
#ifndef SPLINECAL_REPORT_COMMAND_OUTPUTS_H_
#define SPLINECAL_REPORT_COMMAND_OUTPUTS_H_

#include <vector>

#include "splinecal/allan/allan.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/fit.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/report/allan_report.h"
#include "splinecal/report/calibrate_report.h"
#include "splinecal/report/fit_report.h"
#include "splinecal/report/intrinsics_report.h"
#include "splinecal/report/simulate_report.h"
#include "splinecal/sim/simulation_result.h"
#include "splinecal/vio/align.h"

namespace splinecal {

// allan: allan.csv, imu.yaml, result.yaml, allan.svg.
std::vector<OutputFile> AllanOutputFiles(const AllanResult& result);

// simulate: [observations.csv, camchain.yaml with cameras,] mav0/imu0/data.csv,
// mav0/state_groundtruth_estimate0/data.csv, spline.csv, imu.yaml, result.yaml.
std::vector<OutputFile> SimulationOutputFiles(const SimulationRun& run);

// fit: result.yaml, spline.csv, residuals.csv, pose_residuals.csv, report.html.
std::vector<OutputFile> FitOutputFiles(const FitResult& result, const FitReportInputs& inputs);

// calibrate: camchain-imucam.yaml, result.yaml, reprojection_errors.csv, spline.csv,
// report.html.
std::vector<OutputFile> CalibrateOutputFiles(const CalibrationResult& result,
                                             const CalibrateOptions& options,
                                             const CalibrateReportInputs& inputs);

// align: result.yaml, aligned_poses.csv (EuRoC ground-truth format).
std::vector<OutputFile> AlignOutputFiles(const AlignResult& result, const AlignOptions& options);

// intrinsics: camchain.yaml (cameras only, T_cn_cnm1 from cam1 on), result.yaml, report.html,
// and with a per-view inset (in-plane-per-view) view_inset.csv.
std::vector<OutputFile> IntrinsicsOutputFiles(const IntrinsicsResult& result,
                                              const IntrinsicsReportInputs& inputs);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_COMMAND_OUTPUTS_H_
