#include "splinecal/camera/image_bounds_check.h"

#include <cmath>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// Common sensor sizes, to name one that holds the corners (the smallest by area); the exact
// smallest size is named too, since the camera may be none of these.
constexpr int kCommonSizes[][2] = {
    {640, 480},   {752, 480},   {800, 600},   {848, 800},   {1024, 768},  {1280, 720},
    {1280, 800},  {1280, 960},  {1280, 1024}, {1440, 1080}, {1600, 1200}, {1920, 1080},
    {1920, 1200}, {2048, 1536}, {2448, 2048}, {2592, 1944}, {3840, 2160}, {4096, 3000}};

}  // namespace

std::vector<ImageBoundsSummary> SummariseImageBounds(const std::vector<Observation>& observations,
                                                     const std::vector<Camera>& cameras) {
  std::vector<ImageBoundsSummary> summaries(cameras.size());
  for (const Observation& o : observations) {
    if (o.cam_id < 0 || o.cam_id >= static_cast<int>(cameras.size())) continue;
    ImageBoundsSummary& s = summaries[o.cam_id];
    const Camera& camera = cameras[o.cam_id];
    if (s.corners == 0) {
      s.min_uv = s.max_uv = o.uv;
    } else {
      s.min_uv = s.min_uv.cwiseMin(o.uv);
      s.max_uv = s.max_uv.cwiseMax(o.uv);
    }
    ++s.corners;
    const double low = -0.5 - kImageBoundsTolerancePx;
    if (o.uv.x() < low || o.uv.y() < low ||
        o.uv.x() > camera.width - 0.5 + kImageBoundsTolerancePx ||
        o.uv.y() > camera.height - 0.5 + kImageBoundsTolerancePx) {
      ++s.outside;
    }
  }
  for (ImageBoundsSummary& s : summaries) {
    if (s.corners == 0) continue;
    // The image [-0.5, w - 0.5] holds u when w >= u + 0.5 (the tolerance is not used here: the
    // size named must hold every corner).
    s.smallest_fitting_size = Eigen::Vector2i(static_cast<int>(std::ceil(s.max_uv.x() + 0.5)),
                                              static_cast<int>(std::ceil(s.max_uv.y() + 0.5)));
  }
  return summaries;
}

void CheckCornersInsideImages(const std::vector<Observation>& observations,
                              const std::vector<Camera>& cameras,
                              const std::string& observations_name,
                              const std::string& size_source) {
  const std::vector<ImageBoundsSummary> summaries = SummariseImageBounds(observations, cameras);
  for (size_t n = 0; n < cameras.size(); ++n) {
    const ImageBoundsSummary& s = summaries[n];
    if (cameras[n].width <= 0 || cameras[n].height <= 0 || s.outside == 0) continue;
    const Eigen::Vector2i fit = s.smallest_fitting_size;
    std::string fix;
    if (s.min_uv.minCoeff() < -0.5 - kImageBoundsTolerancePx) {
      // Negative pixels: no size holds them; the pixel origin or the camera is wrong.
      fix = StringPrintf("corners at negative u or v (down to %.1f, %.1f): pixels must count "
                         "from the top-left pixel's centre (0, 0), docs/conventions.md",
                         s.min_uv.x(),
                         s.min_uv.y());
    } else {
      fix = StringPrintf("the image is at least %d x %d", fit.x(), fit.y());
      for (const auto& size : kCommonSizes) {
        if (size[0] >= fit.x() && size[1] >= fit.y()) {
          fix += StringPrintf(" (e.g. %d x %d)", size[0], size[1]);
          break;
        }
      }
      fix += ": fix the size in " + size_source;
    }
    throw Error(StringPrintf(
        "%s: cam%zu: %lld of %lld corners lie outside its %d x %d image from %s (largest u "
        "%.1f, v %.1f); %s",
        observations_name.c_str(),
        n,
        static_cast<long long>(s.outside),
        static_cast<long long>(s.corners),
        cameras[n].width,
        cameras[n].height,
        size_source.c_str(),
        s.max_uv.x(),
        s.max_uv.y(),
        fix.c_str()));
  }
}

}  // namespace splinecal
