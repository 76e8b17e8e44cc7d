// What `splinecal intrinsics` writes besides camchain.yaml (docs/intrinsics.md, "Outputs"):
//
//   result.yaml   a `cameras:` list, one entry per camera: camera_model, intrinsics and
//                 distortion_coeffs in Kalibr's order with their stds (intrinsics_std,
//                 distortion_std), resolution, reprojection_rms_px, pixel_sigma_px, the views
//                 (offered, used, and why the others were not), the corners used and rejected
//                 as outliers, and for every camera after the first T_cn_cnm1 with the std of
//                 its rotation [deg] and translation [m] and the baseline |t_cn_cnm1|; then the
//                 solver's figures and the warnings. With --target-deformation other than none,
//                 a `target_deformation:` block (its kind, the coefficients with their stds; out
//                 of plane the heights [mm] at the centre and corners; in plane the x/y scale
//                 ratio, the axes' angle and the tag side and Kalibr's tagSpacing the data say;
//                 per view the insets' count, mean, std, min and max).
//   view_inset.csv  in-plane-per-view only: each timestamp's inset d_v (#t_ns,d).
//   target.yaml, target_points.csv  points only: the refined target (a "points" target file for
//                 calibrate's --target) and each point's position, offset from the file's and
//                 its std [mm] (an empty std for the points that keep the file's position).
//   report.html   the same in tables, and figures: the errors (u/v scatter, norm over time),
//                 the errors against the image position with every corner drawn (where the
//                 image has corners: the coverage; where the model misses: aligned vectors),
//                 and every view's RMS over time, used and set aside. One panel per camera,
//                 parameters by Kalibr's names; the target's deformation in a table.
//   With --compare-models, result.yaml's `model_comparison:` list (per model and camera: RMS,
//   sum of squares, corners, intrinsics and distortion) and report.html's table and error map
//   per model, the arrows of every model at one magnification.
//   summary       the lines printed on stderr.
#ifndef SPLINECAL_REPORT_INTRINSICS_REPORT_H_
#define SPLINECAL_REPORT_INTRINSICS_REPORT_H_

#include <string>
#include <vector>

#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/compare_models.h"

namespace splinecal {

struct IntrinsicsReportInputs {
  std::string observations_path;
  std::string target_path;
  std::string camchain_path;  // empty: not given
  // --compare-models: the models fitted to the same corners (not owned; nullptr: not asked for).
  const std::vector<ModelFit>* model_comparison = nullptr;
};

std::string IntrinsicsResultYaml(const IntrinsicsResult& result,
                                 const std::vector<ModelFit>* model_comparison = nullptr);
std::string IntrinsicsReportHtml(const IntrinsicsResult& result,
                                 const IntrinsicsReportInputs& inputs,
                                 int max_points);
std::string IntrinsicsSummaryText(const IntrinsicsResult& result);
// target_points.csv: "#point_id,x,y,z,dx_mm,dy_mm,dz_mm,std_x_mm,std_y_mm,std_z_mm", one row per
// point of the refined target.
std::string IntrinsicsTargetPointsCsv(const IntrinsicsResult& result);
// view_inset.csv: "#t_ns,d" and one row per timestamp of TargetDeformationResult::view_inset.
std::string IntrinsicsViewInsetCsv(const IntrinsicsResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_INTRINSICS_REPORT_H_
