#include "splinecal/intrinsics/compare_models.h"

#include <algorithm>
#include <cmath>

#include "splinecal/error.h"
#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/string_printf.h"

namespace splinecal {

std::vector<ModelFit> CompareModels(const IntrinsicsResult& result,
                                    const CalibrationTarget& target,
                                    const std::vector<IntrinsicsCameraSpec>& cameras,
                                    const IntrinsicsOptions& options) {
  std::vector<Observation> corners;
  corners.reserve(result.residuals.size());
  for (const ReprojectionSample& s : result.residuals) {
    corners.push_back({s.t_ns, s.cam_id, s.point_id, s.uv});
  }
  // Exact least squares over exactly these corners (header).
  IntrinsicsOptions exact = options;
  exact.outlier_sigmas = 0.0;
  exact.keep_repeated_views = true;
  exact.max_views_per_camera = 0;
  exact.covariance.compute = false;
  exact.solver.progress = nullptr;
  std::vector<ModelFit> fits;
  for (const char* model : kComparedModels) {
    ModelFit& fit = fits.emplace_back();
    fit.model = model;
    std::vector<IntrinsicsCameraSpec> specs;
    for (const IntrinsicsCameraSpec& given : cameras) {
      IntrinsicsCameraSpec spec;
      ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion);
      spec.camera.width = given.camera.width;
      spec.camera.height = given.camera.height;
      specs.push_back(spec);
    }
    try {
      IntrinsicsResult fitted = CalibrateIntrinsics(corners, target, specs, exact);
      fit.cameras = std::move(fitted.cameras);
      fit.residuals = std::move(fitted.residuals);
    } catch (const Error& e) {
      fit.failure = e.what();
      continue;
    }
    fit.sum_of_squares_px2.assign(fit.cameras.size(), 0.0);
    for (const ReprojectionSample& s : fit.residuals) {
      fit.sum_of_squares_px2[s.cam_id] += s.error.squaredNorm();
    }
  }
  return fits;
}

std::string ModelComparisonText(const std::vector<ModelFit>& fits) {
  std::string text =
      "model comparison (exact least squares on the same corners):\n"
      "  camera  model           RMS [px]  sum of squares [px^2]  corners  parameters\n";
  if (fits.empty()) return text;
  size_t num_cameras = 0;
  for (const ModelFit& fit : fits) num_cameras = std::max(num_cameras, fit.cameras.size());
  for (size_t n = 0; n < num_cameras; ++n) {
    for (const ModelFit& fit : fits) {
      if (!fit.failure.empty()) {
        if (n == 0) text += StringPrintf("  %-6s  %-14s  failed: %s\n", "all", fit.model.c_str(),
                                         fit.failure.c_str());
        continue;
      }
      const IntrinsicsCameraResult& c = fit.cameras[n];
      std::string parameters;
      const IntrinsicsVector values = c.camera.intrinsics();
      for (const std::vector<int>& order :
           {KalibrIntrinsicsOrder(c.camera), KalibrDistortionOrder(c.camera)}) {
        for (int i : order) {
          parameters += StringPrintf("%s%s %.*f",
                                     parameters.empty() ? "" : " ",
                                     IntrinsicName(c.camera, i).c_str(),
                                     i < 4 ? 2 : 4,
                                     values(i));
        }
      }
      text += StringPrintf("  cam%-3zu  %-14s  %8.4f  %21.3f  %7d  %s\n",
                           n,
                           fit.model.c_str(),
                           c.reprojection_rms_px,
                           fit.sum_of_squares_px2[n],
                           c.corners_used,
                           parameters.c_str());
    }
  }
  return text;
}

}  // namespace splinecal
