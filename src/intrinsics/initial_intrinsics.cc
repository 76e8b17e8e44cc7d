#include "splinecal/intrinsics/initial_intrinsics.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/camera/pnp.h"
#include "splinecal/median.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

// [Hartley04] R. Hartley, A. Zisserman, Multiple View Geometry, 2nd ed. (normalised DLT).
namespace splinecal {
namespace {

// The similarity that moves `points` to their centroid and scales their RMS distance from it
// to sqrt(2), so that the DLT's rows are equally weighted [Hartley04, 4.4.4].
Eigen::Matrix3d CentreAndScale(const std::vector<Eigen::Vector2d>& points) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d& p : points) centroid += p;
  centroid /= static_cast<double>(points.size());
  double sum_sq = 0.0;
  for (const Eigen::Vector2d& p : points) sum_sq += (p - centroid).squaredNorm();
  const double rms = std::sqrt(sum_sq / static_cast<double>(points.size()));
  const double k = rms > 0.0 ? std::sqrt(2.0) / rms : 1.0;
  Eigen::Matrix3d T = Eigen::Matrix3d::Identity();
  T.topLeftCorner<2, 2>() *= k;
  T.topRightCorner<2, 1>() = -k * centroid;
  return T;
}

// The spread of the target's depth over a view's corners relative to its mean depth,
// (z_max - z_min) / z_mean, from the plane-to-pixel homography H (direct linear transform,
// both sides normalised, CentreAndScale). H ~ K [r1 r2 t], and K's third row is
// (0 0 1) for any focal length and principal point, so H's third row gives each corner's depth
// z = r13 x + r23 y + t3 up to one scale: the spread needs no intrinsics. Lens distortion bends
// the fit a little; the spread only ranks views. 0 for a non-planar target or too few corners.
double DepthSpread(const TargetView& view) {
  const size_t n = view.corners.size();
  if (n < 4) return 0.0;
  // Every stride-th corner, up to kSpreadCorners over the whole board: a ranking needs no
  // more, and the homographies of every view of a long recording cost less.
  constexpr size_t kSpreadCorners = 36;
  const size_t stride = (n + kSpreadCorners - 1) / kSpreadCorners;
  std::vector<Eigen::Vector2d> xy;
  std::vector<Eigen::Vector2d> uv;
  for (size_t i = 0; i < n; i += stride) {
    const TargetCornerObservation& c = view.corners[i];
    if (c.p_t.z() != 0.0) return 0.0;
    xy.push_back(c.p_t.head<2>());
    uv.push_back(c.uv);
  }
  const Eigen::Matrix3d Ta = CentreAndScale(xy);
  const Eigen::Matrix3d Tp = CentreAndScale(uv);
  // The normal equations of the DLT's rows (9 x 9): its smallest eigenvector is H's.
  Eigen::Matrix<double, 9, 9> AtA = Eigen::Matrix<double, 9, 9>::Zero();
  for (size_t i = 0; i < xy.size(); ++i) {
    const Eigen::Vector3d a = Ta * xy[i].homogeneous();
    const Eigen::Vector3d b = Tp * uv[i].homogeneous();
    Eigen::Matrix<double, 9, 1> r1;
    Eigen::Matrix<double, 9, 1> r2;
    r1 << Eigen::Vector3d::Zero(), -b.z() * a, b.y() * a;
    r2 << b.z() * a, Eigen::Vector3d::Zero(), -b.x() * a;
    AtA += r1 * r1.transpose() + r2 * r2.transpose();
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(AtA);
  const Eigen::Matrix<double, 9, 1> h = eigen.eigenvectors().col(0);
  // Tp's third row is (0 0 1): the depth row of H is that of Tp^-1 H_n Ta, h's last three.
  const Eigen::RowVector3d depth_row = h.tail<3>().transpose() * Ta;
  double z_min = std::numeric_limits<double>::infinity();
  double z_max = -z_min;
  double z_sum = 0.0;
  for (const Eigen::Vector2d& p : xy) {
    const double z = depth_row.dot(p.homogeneous());
    z_min = std::min(z_min, z);
    z_max = std::max(z_max, z);
    z_sum += z;
  }
  const double z_mean = std::abs(z_sum) / static_cast<double>(xy.size());
  return z_mean > 0.0 && std::isfinite(z_max - z_min) ? (z_max - z_min) / z_mean : 0.0;
}

// The kInitViews views the candidates are scored on: those with the most perspective, spread
// over the recording. A camera sees its focal length only through perspective: under an affine
// camera (a target with no depth spread, fronto-parallel or far) f trades exactly with the
// distance, and PnP fits every focal length alike, to the lens distortion's misfit. A median
// over such views is flat in f and its minimum falls anywhere (a simulated radtan lens with 7
// of 12 views within 12 degrees of fronto-parallel: the grid's smallest focal, 75 px for a
// true 458). The views are cut into 2 kInitViews runs by time; each run offers its view with
// the largest depth spread (DepthSpread) among those with at least half of the run's most
// corners (a partial view's homography is poorly fixed), ties to more corners; the kInitViews
// offers with the largest spread are scored, in time order.
std::vector<const TargetView*> SweepViews(const std::vector<const TargetView*>& views) {
  const size_t n = views.size();
  const size_t runs = std::min<size_t>(2 * kInitViews, n);
  struct Offer {
    size_t index;
    double spread;
  };
  std::vector<Offer> offers;
  for (size_t r = 0; r < runs; ++r) {
    const size_t begin = r * n / runs;
    const size_t end = (r + 1) * n / runs;
    size_t most_corners = 0;
    for (size_t i = begin; i < end; ++i) {
      most_corners = std::max(most_corners, views[i]->corners.size());
    }
    Offer best{begin, -1.0};
    // About kSpreadViewsPerRun views of a run, evenly spaced: neighbouring frames of a long
    // recording are near repeats of each other.
    constexpr size_t kSpreadViewsPerRun = 4;
    const size_t step = std::max<size_t>(1, (end - begin) / kSpreadViewsPerRun);
    for (size_t i = begin; i < end; i += step) {
      if (2 * views[i]->corners.size() < most_corners) continue;
      const double spread = DepthSpread(*views[i]);
      if (spread > best.spread ||
          (spread == best.spread && views[i]->corners.size() > views[best.index]->corners.size())) {
        best = Offer{i, spread};
      }
    }
    offers.push_back(best);
  }
  std::stable_sort(offers.begin(), offers.end(),
                   [](const Offer& a, const Offer& b) { return a.spread > b.spread; });
  offers.resize(std::min<size_t>(kInitViews, offers.size()));
  std::sort(offers.begin(), offers.end(),
            [](const Offer& a, const Offer& b) { return a.index < b.index; });
  std::vector<const TargetView*> chosen;
  for (const Offer& offer : offers) chosen.push_back(views[offer.index]);
  return chosen;
}

// The median PnP RMS of `camera` over `views` (a failed PnP counts as infinite), or infinity
// as soon as the median cannot be below `bound`. The median is the upper one (median.h), the
// element at n/2 in sorted order, so it is >= bound once n - n/2 views have an RMS >= bound:
// the remaining views are not solved. An exact early exit: no candidate that could beat `bound`
// is dropped.
double Score(const Camera& camera,
             const std::vector<const TargetView*>& views,
             double bound) {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  const size_t enough_to_lose = views.size() - views.size() / 2;
  std::vector<double> rms;
  size_t at_or_above = 0;
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
    rms.push_back(pnp.ok && 2 * p_t.size() >= view->corners.size() ? pnp.rms_px : kInf);
    if (rms.back() >= bound && ++at_or_above >= enough_to_lose) return kInf;
  }
  return rms.empty() ? kInf : Median(std::move(rms));
}

// The focal length of sweep step k (0 .. kFocalSteps - 1) for an image `width` px wide.
double FocalOfStep(int k, double width) {
  return kMinFocalWidths * width *
         std::pow(kMaxFocalWidths / kMinFocalWidths, k / (kFocalSteps - 1.0));
}

// One point of the sweep: a shape candidate (index into ShapeCandidates) and a focal step.
struct SweepPoint {
  size_t shape = 0;
  int step = 0;
  double score = std::numeric_limits<double>::infinity();
};

// Scores the sweep points one by one and keeps the `keep` lowest scores, lowest first. A point
// is scored against the worst kept score (early exit in Score), so only the kept ones carry an
// exact score. Points are visited in the caller's order and ties keep the earlier point, as a
// plain loop with `score < best` does.
class SweepRanking {
 public:
  SweepRanking(const std::vector<Camera>& shapes,
               const std::vector<const TargetView*>& views,
               double width,
               size_t keep)
      : shapes_(shapes), views_(views), width_(width), keep_(keep) {}

  void Try(size_t shape, int step) {
    if (step < 0 || step >= kFocalSteps) return;
    const size_t index = shape * kFocalSteps + static_cast<size_t>(step);
    if (tried_.size() <= index) tried_.resize(shapes_.size() * kFocalSteps, false);
    if (tried_[index]) return;
    tried_[index] = true;
    ++count_;
    Camera candidate = shapes_[shape];
    candidate.fu = candidate.fv = FocalOfStep(step, width_);
    const double bound = best_.size() < keep_ ? std::numeric_limits<double>::infinity()
                                              : best_.back().score;
    const double score = Score(candidate, views_, bound);
    if (score < bound) Insert(SweepPoint{shape, step, score});
  }

  // Takes a point already scored by another ranking without solving it again.
  void Add(const SweepPoint& point) {
    tried_.resize(shapes_.size() * kFocalSteps, false);
    tried_[point.shape * kFocalSteps + static_cast<size_t>(point.step)] = true;
    Insert(point);
  }

  const std::vector<SweepPoint>& best() const { return best_; }
  int count() const { return count_; }

 private:
  void Insert(const SweepPoint& point) {
    auto at = std::upper_bound(best_.begin(), best_.end(), point.score,
                               [](double s, const SweepPoint& p) { return s < p.score; });
    best_.insert(at, point);
    if (best_.size() > keep_) best_.pop_back();
  }

  const std::vector<Camera>& shapes_;
  const std::vector<const TargetView*>& views_;
  double width_;
  size_t keep_;
  std::vector<bool> tried_;
  std::vector<SweepPoint> best_;
  int count_ = 0;
};

}  // namespace

InitialIntrinsics InitialiseIntrinsics(const Camera& model,
                                       const std::vector<const TargetView*>& views,
                                       IntrinsicsSweep sweep) {
  InitialIntrinsics result;
  const std::vector<const TargetView*> scored = SweepViews(views);
  const double width = model.width > 0 ? model.width : 640.0;
  std::vector<Camera> shapes = ShapeCandidates(model);
  for (Camera& shape : shapes) {
    shape.pu = 0.5 * (shape.width - 1);
    shape.pv = 0.5 * (shape.height - 1);
  }
  SweepPoint winner;
  int tried = 0;
  if (sweep == IntrinsicsSweep::kExhaustive) {
    SweepRanking ranking(shapes, scored, width, 1);
    for (size_t s = 0; s < shapes.size(); ++s) {
      for (int k = 0; k < kFocalSteps; ++k) ranking.Try(s, k);
    }
    if (!ranking.best().empty()) winner = ranking.best().front();
    tried = ranking.count();
  } else {
    // Coarse: every kCoarseFocalStride-th step of every shape, the kCoarseSeeds best kept.
    // They are visited from a focal of one image width outwards: most lenses are near it, so
    // the early exit gets a tight bound sooner. The order changes the cost, not the ranking.
    std::vector<int> coarse_steps;
    for (int k = 0; k < kFocalSteps; k += kCoarseFocalStride) coarse_steps.push_back(k);
    const double one_width_step =
        (kFocalSteps - 1.0) * std::log(1.0 / kMinFocalWidths) /
        std::log(kMaxFocalWidths / kMinFocalWidths);
    std::stable_sort(coarse_steps.begin(), coarse_steps.end(), [&](int a, int b) {
      return std::abs(a - one_width_step) < std::abs(b - one_width_step);
    });
    SweepRanking coarse(shapes, scored, width, kCoarseSeeds);
    for (int k : coarse_steps) {
      for (size_t s = 0; s < shapes.size(); ++s) coarse.Try(s, k);
    }
    // Fine: the skipped steps within kCoarseFocalStride - 1 of each seed, each seed's score
    // carried over. With no seed (no coarse candidate placed the target) every step is tried.
    const std::vector<SweepPoint> seeds = coarse.best();
    SweepRanking fine(shapes, scored, width, 1);
    for (const SweepPoint& seed : seeds) fine.Add(seed);
    for (const SweepPoint& seed : seeds) {
      for (int d = 1; d < kCoarseFocalStride; ++d) {
        fine.Try(seed.shape, seed.step - d);
        fine.Try(seed.shape, seed.step + d);
      }
    }
    if (seeds.empty()) {
      for (size_t s = 0; s < shapes.size(); ++s) {
        for (int k = 0; k < kFocalSteps; ++k) fine.Try(s, k);
      }
    }
    if (!fine.best().empty()) winner = fine.best().front();
    tried = coarse.count() + fine.count();
  }
  const double best = winner.score;
  if (std::isfinite(best)) {
    result.camera = shapes[winner.shape];
    result.camera.fu = result.camera.fv = FocalOfStep(winner.step, width);
  }
  result.ok = std::isfinite(best);
  result.median_rms_px = best;
  if (result.ok && (winner.step == 0 || winner.step == kFocalSteps - 1)) {
    // The score may still fall beyond the grid: the lens is outside the sweep's range, or the
    // views do not fix the focal length. A pinhole's horizontal field of view names the edge.
    const bool smallest = winner.step == 0;
    result.at_grid_edge = true;
    result.warning = StringPrintf(
        "the starting-point sweep's best focal length, %.1f px, is its grid's %s (%.3g image "
        "widths, a pinhole's %.0f deg horizontal field of view): the lens may lie beyond the "
        "sweep or the views may not fix its focal length (check fu, fv)",
        result.camera.fu,
        smallest ? "smallest" : "largest",
        smallest ? kMinFocalWidths : kMaxFocalWidths,
        2.0 * std::atan(0.5 / (smallest ? kMinFocalWidths : kMaxFocalWidths)) * kRadToDeg);
  }
  if (result.ok) {
    const Eigen::Vector2d shape = result.camera.projection_params;
    result.description = StringPrintf(
        "sweep of %d candidates (focal %.3g to %.3g px, %zu shape value(s)) on %zu views: f = "
        "%.1f px, shape (%.3g, %.3g), median PnP RMS %.2f px",
        tried,
        kMinFocalWidths * width,
        kMaxFocalWidths * width,
        shapes.size(),
        scored.size(),
        result.camera.fu,
        shape.x(),
        shape.y(),
        best);
  } else {
    result.description = StringPrintf(
        "no candidate of %d placed the target in any of %zu views", tried, scored.size());
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
