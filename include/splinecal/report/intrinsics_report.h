// What `splinecal intrinsics` writes besides camchain.yaml (docs/intrinsics.md, "Outputs"):
//
//   result.yaml   a `cameras:` list, one entry per camera: camera_model, intrinsics and
//                 distortion_coeffs in Kalibr's order with their stds (intrinsics_std,
//                 distortion_std), resolution, reprojection_rms_px, pixel_sigma_px, the views
//                 (offered, used, and why the others were not), the corners used and rejected
//                 as outliers, and for every camera after the first T_cn_cnm1 with the std of
//                 its rotation [deg] and translation [m] and the baseline |t_cn_cnm1|; then the
//                 solver's figures and the warnings.
//   report.html   the same in tables, and figures: the errors (u/v scatter, norm over time),
//                 the errors against the image position with every corner drawn (where the
//                 image has corners: the coverage; where the model misses: aligned vectors),
//                 and every view's RMS over time, used and set aside.
//   summary       the lines printed on stderr.
#ifndef SPLINECAL_REPORT_INTRINSICS_REPORT_H_
#define SPLINECAL_REPORT_INTRINSICS_REPORT_H_

#include <string>
#include <vector>

#include "splinecal/intrinsics/calibrate_intrinsics.h"

namespace splinecal {

struct IntrinsicsReportInputs {
  std::string observations_path;
  std::string target_path;
  std::string camchain_path;  // empty: not given
};

// Kalibr's order of the intrinsics (indices into the layout of camera/camera_model.h):
// pinhole [fu fv pu pv], omni [xi fu fv pu pv], eucm [alpha beta fu fv pu pv],
// ds [xi alpha fu fv pu pv]; and of the distortion coefficients (radtan k1 k2 p1 p2 [k3],
// equidistant k1..k4, fov w, none: none).
std::vector<int> KalibrIntrinsicsOrder(const Camera& camera);
std::vector<int> KalibrDistortionOrder(const Camera& camera);

std::string IntrinsicsResultYaml(const IntrinsicsResult& result);
std::string IntrinsicsReportHtml(const IntrinsicsResult& result,
                                 const IntrinsicsReportInputs& inputs,
                                 int max_points);
std::string IntrinsicsSummaryText(const IntrinsicsResult& result);

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_INTRINSICS_REPORT_H_
