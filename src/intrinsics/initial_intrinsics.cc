#include "splinecal/intrinsics/initial_intrinsics.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/camera/pnp.h"
#include "splinecal/median.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// Up to kInitViews views with the most corners, spread over the recording: the views are cut
// into kInitViews runs by time and each run gives its fullest view.
std::vector<const TargetView*> SpreadViews(const std::vector<const TargetView*>& views) {
  std::vector<const TargetView*> chosen;
  const size_t n = views.size();
  const size_t runs = std::min<size_t>(kInitViews, n);
  for (size_t r = 0; r < runs; ++r) {
    const size_t begin = r * n / runs;
    const size_t end = (r + 1) * n / runs;
    const TargetView* best = views[begin];
    for (size_t i = begin; i < end; ++i) {
      if (views[i]->corners.size() > best->corners.size()) best = views[i];
    }
    chosen.push_back(best);
  }
  return chosen;
}

// The median PnP RMS of `camera` over `views` (a failed PnP counts as infinite).
double Score(const Camera& camera, const std::vector<const TargetView*>& views) {
  std::vector<double> rms;
  PnpOptions options;
  options.max_iterations = 15;
  for (const TargetView* view : views) {
    std::vector<Eigen::Vector3d> p_t;
    std::vector<Eigen::Vector2d> uv;
    Eigen::Vector3d ray;
    for (const TargetCornerObservation& c : view->corners) {
      // Corners this candidate cannot unproject (beyond its field of view) are left out; too
      // few left fails the view.
      if (!camera.Unproject(c.uv, &ray)) continue;
      p_t.push_back(c.p_t);
      uv.push_back(c.uv);
    }
    const PnpResult pnp = SolvePnp(camera, p_t, uv, options);
    rms.push_back(pnp.ok && 2 * p_t.size() >= view->corners.size()
                      ? pnp.rms_px
                      : std::numeric_limits<double>::infinity());
  }
  return rms.empty() ? std::numeric_limits<double>::infinity() : Median(std::move(rms));
}

}  // namespace

InitialIntrinsics InitialiseIntrinsics(const Camera& model,
                                       const std::vector<const TargetView*>& views) {
  InitialIntrinsics result;
  const std::vector<const TargetView*> spread = SpreadViews(views);
  const double width = model.width > 0 ? model.width : 640.0;
  double best = std::numeric_limits<double>::infinity();
  int tried = 0;
  for (Camera candidate : ShapeCandidates(model)) {
    candidate.pu = 0.5 * (candidate.width - 1);
    candidate.pv = 0.5 * (candidate.height - 1);
    for (int k = 0; k < kFocalSteps; ++k) {
      const double f = kMinFocalWidths * width *
                       std::pow(kMaxFocalWidths / kMinFocalWidths, k / (kFocalSteps - 1.0));
      candidate.fu = candidate.fv = f;
      ++tried;
      const double score = Score(candidate, spread);
      if (score < best) {
        best = score;
        result.camera = candidate;
      }
    }
  }
  result.ok = std::isfinite(best);
  result.median_rms_px = best;
  if (result.ok) {
    const Eigen::Vector2d shape = result.camera.projection_params;
    result.description = StringPrintf(
        "sweep of %d candidates (focal %.3g to %.3g px, %zu shape value(s)) on %zu views: f = "
        "%.1f px, shape (%.3g, %.3g), median PnP RMS %.2f px",
        tried,
        kMinFocalWidths * width,
        kMaxFocalWidths * width,
        ShapeCandidates(model).size(),
        spread.size(),
        result.camera.fu,
        shape.x(),
        shape.y(),
        best);
  } else {
    result.description = StringPrintf(
        "no candidate of %d placed the target in any of %zu views", tried, spread.size());
  }
  return result;
}

std::vector<Camera> ShapeCandidates(const Camera& model) {
  Camera base = model;
  base.distortion_coeffs.setZero();
  base.projection_params.setZero();
  base.radtan_k3 = model.radtan_k3;
  std::vector<Eigen::Vector2d> shapes;  // projection parameters (m0, m1)
  switch (model.projection) {
    case ProjectionModel::kPinhole:
      shapes = {{0.0, 0.0}};
      break;
    case ProjectionModel::kOmni:  // xi: 0 is a pinhole, about 1 a fisheye [Mei07 init]
      shapes = {{0.0, 0.0}, {0.6, 0.0}, {1.2, 0.0}};
      break;
    case ProjectionModel::kEucm:  // (alpha, beta = 1): alpha 0 is a pinhole
      shapes = {{0.0, 1.0}, {0.4, 1.0}, {0.65, 1.0}};
      break;
    case ProjectionModel::kDoubleSphere:  // (xi, alpha): (0, 0) is a pinhole
      shapes = {{0.0, 0.0}, {0.0, 0.4}, {-0.2, 0.6}};
      break;
  }
  std::vector<double> fov_w = {0.0};
  if (model.distortion == DistortionModel::kFov) fov_w = {0.3, 0.8, 1.3};  // w [rad]
  std::vector<Camera> candidates;
  for (const Eigen::Vector2d& shape : shapes) {
    for (double w : fov_w) {
      Camera candidate = base;
      candidate.projection_params = shape;
      candidate.distortion_coeffs(0) = w;
      candidates.push_back(candidate);
    }
  }
  return candidates;
}

}  // namespace splinecal
