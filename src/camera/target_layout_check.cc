#include "splinecal/camera/target_layout_check.h"

#include <Eigen/Dense>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>

#include "splinecal/error.h"
#include "splinecal/median.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// Frames the check looks at: spread over the recording, enough for thousands of neighbour
// samples on EuRoC imu_april (docs/reliability.md) and a search over the column counts in a
// fraction of a second.
constexpr size_t kMaxFrames = 60;
// The search for the layout the corners fit tries up to this many corners per row (100 tags):
// printed boards have far fewer.
constexpr int64_t kMaxSearchCornerCols = 200;
// Fewer predicted neighbour corners than this: too little seen to judge; the check is silent.
constexpr int kMinSamples = 32;
// A numbering fits when, in each direction, the median prediction error is below kMaxResidual
// [cell sides] and at most kMaxGrossFraction of the predictions are gross (beyond
// kGrossResidual, or failed). The median alone does not do: a numbering off by one column per
// row shears the lattice, and a sheared lattice predicts itself perfectly except where its rows
// wrap around the board's edge, where predictions miss by whole cells. Measured on EuRoC
// imu_april and on synthetic views (tests/camera/target_layout_check_test.cc): right numbering,
// median 0.019 and no gross prediction; wrong ones, docs/reliability.md. The simulated
// wide-angle views of tests/intrinsics/calibrate_intrinsics_test.cc (small cells near the
// border of strongly distorting models) reach a median of 0.08 and 7% gross with the right
// numbering: hence the margins.
constexpr double kMaxResidual = 0.2;
constexpr double kGrossResidual = 0.5;
constexpr double kMaxGrossFraction = 0.2;
// The spacing measured towards the right and upwards must agree this well [tag sides] (a
// numbering with twice the columns puts real rows 2 apart into one cell: the upward "spacing"
// then differs by a whole tag plus a gap).
constexpr double kMaxDirectionDisagreement = 0.05;
// An aprilgrid's tagSpacing differing from the measured one by more than this is refused
// [ratio]. Measured spread on EuRoC imu_april: docs/reliability.md; printed boards use steps
// of 0.05 or more (0.2, 0.25, 0.3).
constexpr double kSpacingTolerance = 0.025;
// A cell's image quadrilateral must turn the same way at every corner with |sin| above this (a
// convex, non-degenerate quadrilateral: a plane seen from its front).
constexpr double kMinCornerSine = 0.1;

const Eigen::Vector2d* FindCorner(const ObservationFrame& frame, int64_t id) {
  const auto it = std::lower_bound(
      frame.observations.begin(), frame.observations.end(), id,
      [](const Observation& o, int64_t value) { return o.point_id < value; });
  return it != frame.observations.end() && it->point_id == id ? &it->uv : nullptr;
}

// The homography from the unit square (corners (0,0), (1,0), (1,1), (0,1)) onto the
// quadrilateral q[0..3], in closed form (P. Heckbert, "Fundamentals of Texture Mapping and
// Image Warping", 1989, section 2.2.3); false for a quadrilateral that is not convex.
bool UnitSquareHomography(const std::array<Eigen::Vector2d, 4>& q, Eigen::Matrix3d* H) {
  double turn = 0.0;
  for (int k = 0; k < 4; ++k) {
    const Eigen::Vector2d in = q[k] - q[(k + 3) % 4];
    const Eigen::Vector2d out = q[(k + 1) % 4] - q[k];
    const double lengths = in.norm() * out.norm();
    if (!(lengths > 0.0)) return false;
    const double sine = (in.x() * out.y() - in.y() * out.x()) / lengths;
    if (std::abs(sine) < kMinCornerSine || sine * turn < 0.0) return false;
    turn = sine;
  }
  const Eigen::Vector2d d1 = q[1] - q[2];
  const Eigen::Vector2d d2 = q[3] - q[2];
  const Eigen::Vector2d d3 = q[0] - q[1] + q[2] - q[3];
  const double det = d1.x() * d2.y() - d2.x() * d1.y();
  const double g = (d3.x() * d2.y() - d2.x() * d3.y()) / det;
  const double h = (d1.x() * d3.y() - d3.x() * d1.y()) / det;
  *H << q[1].x() - q[0].x() + g * q[1].x(), q[3].x() - q[0].x() + h * q[3].x(), q[0].x(),
      q[1].y() - q[0].y() + g * q[1].y(), q[3].y() - q[0].y() + h * q[3].y(), q[0].y(), g, h,
      1.0;
  return H->allFinite();
}

std::string LayoutName(const GridLayout& layout, int64_t max_id, double spacing) {
  const int64_t corner_rows = max_id / layout.corner_cols + 1;
  if (layout.aprilgrid) {
    return StringPrintf("%d x %lld aprilgrid (tagCols x tagRows) with tagSpacing %.2f",
                        layout.corner_cols / 2,
                        static_cast<long long>((corner_rows + 1) / 2),
                        spacing);
  }
  return StringPrintf("%d x %lld checkerboard (targetCols x targetRows)",
                      layout.corner_cols,
                      static_cast<long long>(corner_rows));
}

}  // namespace

GridLayoutFit FitGridLayout(const std::vector<ObservationFrame>& frames, const GridLayout& layout) {
  const int64_t cols = layout.corner_cols;
  GridLayoutFit fit;
  if (cols < 2) return fit;
  std::array<std::vector<double>, 2> along, across;  // [0] right neighbour, [1] upper one
  std::array<int, 2> failed = {0, 0};
  for (const ObservationFrame& frame : frames) {
    auto corner = [&](int64_t r, int64_t c) -> const Eigen::Vector2d* {
      return c < cols ? FindCorner(frame, r * cols + c) : nullptr;
    };
    // Every seen corner at even (row, col) is the origin of a cell (an AprilGrid tag's first
    // corner); cost proportional to the corners seen, not to the grid's size.
    for (const Observation& origin : frame.observations) {
      const int64_t r = origin.point_id / cols;
      const int64_t c = origin.point_id % cols;
      if (r % 2 != 0 || c % 2 != 0) continue;
      const Eigen::Vector2d* q[4] = {
          corner(r, c), corner(r, c + 1), corner(r + 1, c + 1), corner(r + 1, c)};
      if (!q[0] || !q[1] || !q[2] || !q[3]) continue;
      Eigen::Matrix3d H;
      const bool valid = UnitSquareHomography({*q[0], *q[1], *q[2], *q[3]}, &H);
      const Eigen::Matrix3d H_inv = valid ? Eigen::Matrix3d(H.inverse()) : Eigen::Matrix3d::Zero();
      for (int dir = 0; dir < 2; ++dir) {
        for (int a = 0; a < 2; ++a) {
          for (int b = 0; b < 2; ++b) {
            const Eigen::Vector2d* p =
                dir == 0 ? corner(r + a, c + 2 + b) : corner(r + 2 + a, c + b);
            if (p == nullptr) continue;
            const Eigen::Vector3d X = H_inv * p->homogeneous();
            // X.z > 0: the corner is on the cell's side of the plane's horizon.
            if (!valid || !(X.z() > 0.0) || !X.allFinite()) {
              ++failed[dir];
              continue;
            }
            const double x = X.x() / X.z();
            const double y = X.y() / X.z();
            along[dir].push_back(dir == 0 ? x - 1.0 - b : y - 1.0 - a);
            across[dir].push_back(dir == 0 ? y - a : x - b);
          }
        }
      }
    }
  }
  // Each direction on its own (a numbering with twice the columns gets one direction right),
  // then the worse of the directions seen well enough to tell.
  constexpr int kMinPerDirection = 8;
  std::vector<double> all_along;
  double spacing[2];
  fit.residual = 0.0;
  for (int dir = 0; dir < 2; ++dir) {
    const int count = static_cast<int>(along[dir].size()) + failed[dir];
    fit.samples += count;
    fit.failed += failed[dir];
    spacing[dir] = layout.aprilgrid ? Median(along[dir]) : 1.0;
    std::vector<double> residuals(failed[dir], std::numeric_limits<double>::infinity());
    for (size_t k = 0; k < along[dir].size(); ++k) {
      residuals.push_back(std::hypot(along[dir][k] - spacing[dir], across[dir][k]));
    }
    if (count >= kMinPerDirection) {
      const int64_t gross = std::count_if(
          residuals.begin(), residuals.end(), [](double e) { return !(e <= kGrossResidual); });
      fit.gross_fraction =
          std::max(fit.gross_fraction, static_cast<double>(gross) / static_cast<double>(count));
      fit.residual = std::max(fit.residual, Median(residuals));
      ++fit.directions;
    }
    all_along.insert(all_along.end(), along[dir].begin(), along[dir].end());
  }
  fit.spacing_right = spacing[0];
  fit.spacing_up = spacing[1];
  fit.spacing = Median(all_along);
  const bool directions_agree = static_cast<int>(along[0].size()) < kMinPerDirection ||
                                static_cast<int>(along[1].size()) < kMinPerDirection ||
                                std::abs(spacing[0] - spacing[1]) < kMaxDirectionDisagreement;
  // Both directions: along one direction alone many wrong numberings form a consistent
  // (sheared) lattice, e.g. 134 corners per row puts row 0 and row 11 of the 6 x 6 board into one
  // cell, and those cells predict each other perfectly towards the right.
  fit.fits = fit.samples >= kMinSamples && fit.directions == 2 && fit.residual < kMaxResidual &&
             fit.gross_fraction <= kMaxGrossFraction && directions_agree;
  return fit;
}

std::vector<ObservationFrame> LayoutCheckFrames(const std::vector<Observation>& observations,
                                                const CalibrationTarget& target) {
  std::vector<Observation> on_target;
  for (const Observation& o : observations) {
    if (o.point_id >= 0 && target.Find(o.point_id) != nullptr) on_target.push_back(o);
  }
  std::vector<ObservationFrame> frames = GroupIntoFrames(std::move(on_target));
  if (frames.size() <= kMaxFrames) return frames;
  std::vector<ObservationFrame> spread;
  spread.reserve(kMaxFrames);
  for (size_t k = 0; k < kMaxFrames; ++k) {
    spread.push_back(std::move(frames[k * frames.size() / kMaxFrames]));
  }
  return spread;
}

void CheckTargetLayout(const std::vector<Observation>& observations,
                       const CalibrationTarget& target,
                       const std::string& observations_name,
                       const std::string& target_name) {
  const bool aprilgrid = target.type == "aprilgrid";
  if ((!aprilgrid && target.type != "checkerboard") || target.grid_cols <= 0) return;
  const std::vector<ObservationFrame> frames = LayoutCheckFrames(observations, target);
  int64_t max_id = 0;
  for (const ObservationFrame& frame : frames) {
    if (!frame.observations.empty()) {
      max_id = std::max(max_id, frame.observations.back().point_id);
    }
  }
  const GridLayout given{aprilgrid, aprilgrid ? 2 * target.grid_cols : target.grid_cols};
  GridLayoutFit fit = FitGridLayout(frames, given);
  if (fit.samples < kMinSamples) return;  // too little seen to judge
  // A board one cell high (or wide) shows one direction only: judged on that one.
  if (fit.directions == 1 && fit.residual < kMaxResidual &&
      fit.gross_fraction <= kMaxGrossFraction) {
    fit.fits = true;
  }
  const std::string given_name =
      aprilgrid ? StringPrintf("%d x %d aprilgrid (tagSpacing %.2f)",
                               target.grid_cols,
                               target.grid_rows,
                               target.tag_spacing_ratio)
                : StringPrintf("%d x %d checkerboard", target.grid_cols, target.grid_rows);
  const char* keys = aprilgrid ? "tagCols/tagRows" : "targetCols/targetRows";
  if (fit.fits && aprilgrid && std::abs(fit.spacing - 1.0) < kSpacingTolerance &&
      std::abs(target.tag_spacing_ratio - 1.0) >= kSpacingTolerance) {
    // Gaps as wide as the tags: the corners of a checkerboard, numbered row by row.
    throw Error(StringPrintf("%s: the corners fit a %s, not the %s of %s: give the checkerboard "
                             "in %s",
                             observations_name.c_str(),
                             LayoutName({false, given.corner_cols}, max_id, 1.0).c_str(),
                             given_name.c_str(),
                             target_name.c_str(),
                             target_name.c_str()));
  }
  if (fit.fits) {
    if (aprilgrid && std::abs(fit.spacing - target.tag_spacing_ratio) > kSpacingTolerance) {
      throw Error(StringPrintf(
          "%s: the corners fit tagSpacing %.2f (the gap between tags over tagSize, measured "
          "on %d neighbouring-tag corners), not the %.2f of %s: fix tagSpacing in %s",
          observations_name.c_str(),
          fit.spacing,
          fit.samples - fit.failed,
          target.tag_spacing_ratio,
          target_name.c_str(),
          target_name.c_str()));
    }
    return;
  }
  // Which numbering do the corners fit? The target's own kind first, then the other; among the
  // numberings that fit, the one with the smallest prediction error.
  GridLayout best;
  GridLayoutFit best_fit;
  for (const bool kind : {aprilgrid, !aprilgrid}) {
    for (int64_t cols = 2; cols <= std::min(max_id + 1, kMaxSearchCornerCols);
         cols += kind ? 2 : 1) {
      const GridLayout layout{kind, static_cast<int>(cols)};
      const GridLayoutFit candidate = FitGridLayout(frames, layout);
      if (candidate.fits &&
          (best.corner_cols == 0 || candidate.residual < best_fit.residual)) {
        best = layout;
        best_fit = candidate;
      }
    }
    if (best.corner_cols > 0) break;
  }
  const std::string why = StringPrintf(
      "numbered as %d corners per row, %.0f%% of the neighbouring cells' corners land over %.1f "
      "cell sides from where the grid puts them, median %.2f (a matching grid: under %.0f%%, "
      "median under %.1f)",
      given.corner_cols,
      100.0 * fit.gross_fraction,
      kGrossResidual,
      fit.residual,
      100.0 * kMaxGrossFraction,
      kMaxResidual);
  if (best.corner_cols > 0) {
    // The file's own spacing when the corners agree with it (the measured one carries the
    // lens's small bias: 0.309 for EuRoC's 0.3), else the measured one.
    const double spacing =
        aprilgrid && std::abs(best_fit.spacing - target.tag_spacing_ratio) <= kSpacingTolerance
            ? target.tag_spacing_ratio
            : best_fit.spacing;
    throw Error(StringPrintf("%s: the corners fit a %s, not the %s of %s (%s): fix %s in %s",
                             observations_name.c_str(),
                             LayoutName(best, max_id, spacing).c_str(),
                             given_name.c_str(),
                             target_name.c_str(),
                             why.c_str(),
                             best.aprilgrid == aprilgrid ? keys : "the target file",
                             target_name.c_str()));
  }
  throw Error(StringPrintf(
      "%s: the corners do not fit the %s of %s (%s), nor any aprilgrid or checkerboard of up "
      "to %lld corners per row: wrong target file, or the detector numbers corners another way",
      observations_name.c_str(),
      given_name.c_str(),
      target_name.c_str(),
      why.c_str(),
      static_cast<long long>(std::min(max_id + 1, kMaxSearchCornerCols))));
}

}  // namespace splinecal
