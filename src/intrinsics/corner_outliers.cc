#include "splinecal/intrinsics/corner_outliers.h"

#include <algorithm>
#include <cmath>

#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/intrinsics/local_corner_fit.h"
#include "splinecal/median.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// 1.4826 x the median absolute value: the std of Gaussian noise, robustly. A floor keeps
// noise-free simulations (scale ~ 0) from rejecting round-off.
double RobustScale(const std::vector<double>& absolute_components) {
  return std::max(1.4826 * Median(absolute_components), 1e-6);
}

int CellOf(const Eigen::Vector2d& uv, int width, int height) {
  const int cu =
      std::clamp(static_cast<int>(uv.x() / width * kCoverageCells), 0, kCoverageCells - 1);
  const int cv =
      std::clamp(static_cast<int>(uv.y() / height * kCoverageCells), 0, kCoverageCells - 1);
  return cv * kCoverageCells + cu;
}

bool AtBorder(int cell) {
  const int cu = cell % kCoverageCells;
  const int cv = cell / kCoverageCells;
  return cu == 0 || cv == 0 || cu == kCoverageCells - 1 || cv == kCoverageCells - 1;
}

}  // namespace

CornerOutliers FindCornerOutliers(const std::vector<ViewErrors>& views,
                                  int width,
                                  int height,
                                  double outlier_sigmas) {
  constexpr int kCells = kCoverageCells * kCoverageCells;
  CornerOutliers out;
  out.outlier.resize(views.size());
  // The cells' median misfit.
  std::vector<std::vector<double>> ex(kCells), ey(kCells);
  std::vector<double> all;
  for (const ViewErrors& view : views) {
    for (size_t i = 0; i < view.error.size(); ++i) {
      if (!view.error[i].allFinite()) continue;
      const int c = CellOf(view.uv[i], width, height);
      ex[c].push_back(view.error[i].x());
      ey[c].push_back(view.error[i].y());
      all.push_back(std::abs(view.error[i].x()));
      all.push_back(std::abs(view.error[i].y()));
    }
  }
  out.sigma_px = RobustScale(all);
  std::vector<Eigen::Vector2d> misfit(kCells, Eigen::Vector2d::Zero());
  for (int c = 0; c < kCells; ++c) {
    if (static_cast<int>(ex[c].size()) >= kMinCellCorners) {
      misfit[c] = Eigen::Vector2d(Median(ex[c]), Median(ey[c]));
    }
  }
  // The cells' and the views' scales of the errors beyond the misfit.
  std::vector<std::vector<double>> cell_components(kCells);
  std::vector<std::vector<Eigen::Vector2d>> beyond(views.size());
  std::vector<double> view_scale(views.size(), 0.0);
  for (size_t v = 0; v < views.size(); ++v) {
    std::vector<double> components;
    for (size_t i = 0; i < views[v].error.size(); ++i) {
      const int c = CellOf(views[v].uv[i], width, height);
      const Eigen::Vector2d d = views[v].error[i] - misfit[c];
      beyond[v].push_back(d);
      if (!d.allFinite()) continue;
      for (double x : {std::abs(d.x()), std::abs(d.y())}) {
        components.push_back(x);
        cell_components[c].push_back(x);
      }
    }
    view_scale[v] = RobustScale(components);
  }
  std::vector<double> cell_scale(kCells, out.sigma_px);
  for (int c = 0; c < kCells; ++c) {
    if (static_cast<int>(cell_components[c].size()) >= 2 * kMinCellCorners) {
      cell_scale[c] = RobustScale(cell_components[c]);
    }
  }
  // The model-free test's residuals and their scales, camera-wide and per view.
  std::vector<std::vector<Eigen::Vector2d>> local(views.size());
  std::vector<double> local_view_scale(views.size(), 0.0);
  std::vector<double> local_all;
  for (size_t v = 0; v < views.size(); ++v) {
    if (outlier_sigmas > 0.0 && !views[v].p_t.empty()) {
      local[v] = LocalFitResiduals(views[v].p_t, views[v].uv);
    }
    std::vector<double> components;
    for (const Eigen::Vector2d& l : local[v]) {
      if (!l.allFinite()) continue;
      for (double x : {std::abs(l.x()), std::abs(l.y())}) components.push_back(x);
    }
    local_all.insert(local_all.end(), components.begin(), components.end());
    if (!components.empty()) local_view_scale[v] = RobustScale(components);
  }
  const double local_scale = local_all.empty() ? 0.0 : RobustScale(local_all);
  for (size_t v = 0; v < views.size(); ++v) {
    out.outlier[v].assign(views[v].error.size(), false);
    for (size_t i = 0; i < views[v].error.size(); ++i) {
      ++out.corners;
      const int c = CellOf(views[v].uv[i], width, height);
      if (!beyond[v][i].allFinite()) {
        out.outlier[v][i] = true;
        ++out.removed;
        if (AtBorder(c)) ++out.removed_at_border;
        continue;
      }
      const double limit = outlier_sigmas * std::max(cell_scale[c], view_scale[v]);
      if (!(outlier_sigmas > 0.0 && beyond[v][i].norm() > limit)) continue;
      const bool judged = i < local[v].size() && local[v][i].allFinite();
      const double local_limit = outlier_sigmas * std::max(local_scale, local_view_scale[v]);
      if (judged && local[v][i].norm() <= local_limit) {
        ++out.kept_misfit;
        if (AtBorder(c)) ++out.kept_misfit_at_border;
        continue;
      }
      out.outlier[v][i] = true;
      ++out.removed;
      if (AtBorder(c)) ++out.removed_at_border;
    }
  }
  return out;
}

std::string CornerOutlierWarning(const std::string& camera_name,
                                 const std::string& model_name,
                                 const CornerOutliers& outliers) {
  if (outliers.corners == 0) return "";
  std::string text;
  if (outliers.removed > kOutlierWarningShare * outliers.corners) {
    text = StringPrintf(
        "%s: %d of %d corners (%.1f%%) removed as outliers (far from the model's fit and from "
        "their neighbours on the target)",
        camera_name.c_str(),
        outliers.removed,
        outliers.corners,
        100.0 * outliers.removed / outliers.corners);
  }
  // The outer ring holds 28 of the 64 cells; a share well above it says where the misfit is.
  constexpr double kBorderCells = 4.0 * (kCoverageCells - 1) / (kCoverageCells * kCoverageCells);
  const int misfit = outliers.kept_misfit;
  const double at_border =
      misfit > 0 ? static_cast<double>(outliers.kept_misfit_at_border) / misfit : 0.0;
  const bool border = misfit >= kMinBorderCorners && at_border > 1.5 * kBorderCells;
  if (!border && misfit <= kOutlierWarningShare * outliers.corners) return text;
  if (!text.empty()) text += "; ";
  text += StringPrintf(
      "%s: %d of %d corners (%.1f%%) lie beyond the outlier limit of %s's fit but agree with "
      "their neighbours on the target (kept: the model misfits them), %.0f%% of them at the image "
      "border",
      camera_name.c_str(),
      misfit,
      outliers.corners,
      100.0 * misfit / outliers.corners,
      model_name.c_str(),
      100.0 * at_border);
  if (border) {
    // Wide-angle models that describe a lens's border where radtan's polynomial cannot.
    std::string others;
    for (const char* other : {"pinhole-equi", "ds-none", "eucm-none"}) {
      if (model_name == other || std::count(others.begin(), others.end(), ' ') >= 2) continue;
      others += (others.empty() ? "" : " or ") + std::string(other);
    }
    text += StringPrintf(": %s likely misfits the border (try %s)",
                         model_name.c_str(),
                         others.c_str());
  }
  return text;
}

}  // namespace splinecal
