#include "splinecal/report/command_outputs.h"

#include "splinecal/io/target_yaml.h"

#include <sstream>
#include <string>

#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/align_report.h"

namespace splinecal {

namespace {

// At most this many points per series in intrinsics' report.html (the command's choice).
constexpr int kIntrinsicsReportMaxPoints = 3000;

std::string SplineCsvText(const SE3Splined& spline) {
  std::ostringstream csv;
  WriteSplineCsv(spline, &csv);
  return csv.str();
}

std::string GroundTruthCsvText(const std::vector<GroundTruthState>& states) {
  std::ostringstream csv;
  WriteEurocGroundTruth(states, &csv);
  return csv.str();
}

}  // namespace

std::vector<OutputFile> AllanOutputFiles(const AllanResult& result) {
  return {{"allan.csv", AllanCsvText(result)},
          {"imu.yaml", AllanImuYamlText(result)},
          {"result.yaml", AllanResultYamlText(result)},
          {"allan.svg", AllanSvgText(result)}};
}

std::vector<OutputFile> SimulationOutputFiles(const SimulationRun& run) {
  std::vector<OutputFile> files;
  if (!run.camchain.empty()) {
    std::ostringstream observations_csv;
    WriteObservationsCsv(run.cameras.observations, &observations_csv);
    files.push_back({"observations.csv", observations_csv.str()});
    files.push_back({"camchain.yaml", CamchainYamlText(run.camchain)});
  }
  std::ostringstream imu_csv;
  WriteEurocImu(run.imu, &imu_csv);
  files.push_back({"mav0/imu0/data.csv", imu_csv.str()});
  for (size_t k = 0; k < run.more_imu.size(); ++k) {
    std::ostringstream more_csv;
    WriteEurocImu(run.more_imu[k], &more_csv);
    files.push_back({"mav0/imu" + std::to_string(k + 1) + "/data.csv", more_csv.str()});
  }
  if (HasImuModels(run)) files.push_back({"imu_models.yaml", SimulationImuModelsYaml(run)});
  files.push_back({"mav0/state_groundtruth_estimate0/data.csv", GroundTruthCsvText(run.truth)});
  files.push_back({"spline.csv", SplineCsvText(run.spline.fit.MakeSpline())});
  files.push_back({"imu.yaml", ImuYamlText(run.options.noise)});
  files.push_back({"result.yaml", SimulationResultYaml(run)});
  return files;
}

std::vector<OutputFile> FitOutputFiles(const FitResult& result, const FitReportInputs& inputs) {
  return {{"result.yaml", FitResultYaml(result, inputs)},
          {"spline.csv", SplineCsvText(result.MakeSpline())},
          {"residuals.csv", FitResidualsCsv(result)},
          {"pose_residuals.csv", FitPoseResidualsCsv(result)},
          {"report.html", FitReportHtml(result, inputs)}};
}

std::vector<OutputFile> CalibrateOutputFiles(const CalibrationResult& result,
                                             const CalibrateOptions& options,
                                             const CalibrateReportInputs& inputs) {
  std::vector<OutputFile> files = {
      {"camchain-imucam.yaml", CamchainYamlText(result.camchain)},
      {"result.yaml", CalibrateResultYaml(result, options)},
      {"reprojection_errors.csv", CalibrateReprojectionCsv(result)},
      {"spline.csv", SplineCsvText(result.MakeSpline())},
      {"report.html", CalibrateReportHtml(result, options, inputs)}};
  // Kalibr's imu-*.yaml (io/imu_models_yaml.h) when an IMU model was estimated: the file
  // `splinecal correct` applies to raw readings.
  // With several IMUs: imu0 the reference, then each further IMU (T_i_b, time_offset).
  if (result.imu_model.model != ImuModelKind::kCalibrated || !result.further_imus.empty()) {
    std::vector<ImuCalibration> imus = {result.imu_model};
    for (const FurtherImuEstimate& e : result.further_imus) imus.push_back(e.calibration);
    files.push_back({"imu_models.yaml", ImuModelsYamlText(imus)});
  }
  return files;
}

std::vector<OutputFile> AlignOutputFiles(const AlignResult& result, const AlignOptions& options) {
  return {{"result.yaml", AlignResultYaml(result, options)},
          {"aligned_poses.csv", GroundTruthCsvText(result.states_w)}};
}

std::vector<OutputFile> IntrinsicsOutputFiles(const IntrinsicsResult& result,
                                              const IntrinsicsReportInputs& inputs) {
  Camchain camchain;
  for (size_t n = 0; n < result.cameras.size(); ++n) {
    CameraCalibration calibration;
    calibration.camera = result.cameras[n].camera;
    if (n > 0) calibration.T_cn_cnm1 = result.cameras[n].T_cn_cnm1;
    camchain.push_back(calibration);
  }
  // Each camera's covariance (splinecal_covariance) rides along, for calibrate's priors.
  std::vector<ParameterCovariance> covariances;
  for (const IntrinsicsCameraResult& camera : result.cameras) {
    covariances.push_back(camera.covariance);
  }
  std::vector<OutputFile> files = {
      {"camchain.yaml", CamchainYamlText(camchain, CamchainKeys::kCamerasOnly, covariances)},
      {"result.yaml", IntrinsicsResultYaml(result, inputs.model_comparison)},
      {"report.html", IntrinsicsReportHtml(result, inputs, kIntrinsicsReportMaxPoints)}};
  if (result.target_deformation.shape.per_view_inset()) {
    files.push_back({"view_inset.csv", IntrinsicsViewInsetCsv(result)});
  }
  if (result.target_deformation.shape.per_point()) {
    files.push_back({"target.yaml", TargetPointsYamlText(result.target_deformation.refined_target)});
    files.push_back({"target_points.csv", IntrinsicsTargetPointsCsv(result)});
  }
  return files;
}

}  // namespace splinecal
