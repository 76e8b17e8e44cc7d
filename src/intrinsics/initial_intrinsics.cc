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
  const std::vector<const TargetView*> spread = SpreadViews(views);
  const double width = model.width > 0 ? model.width : 640.0;
  std::vector<Camera> shapes = ShapeCandidates(model);
  for (Camera& shape : shapes) {
    shape.pu = 0.5 * (shape.width - 1);
    shape.pv = 0.5 * (shape.height - 1);
  }
  SweepPoint winner;
  int tried = 0;
  if (sweep == IntrinsicsSweep::kExhaustive) {
    SweepRanking ranking(shapes, spread, width, 1);
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
    SweepRanking coarse(shapes, spread, width, kCoarseSeeds);
    for (int k : coarse_steps) {
      for (size_t s = 0; s < shapes.size(); ++s) coarse.Try(s, k);
    }
    // Fine: the skipped steps within kCoarseFocalStride - 1 of each seed, each seed's score
    // carried over. With no seed (no coarse candidate placed the target) every step is tried.
    const std::vector<SweepPoint> seeds = coarse.best();
    SweepRanking fine(shapes, spread, width, 1);
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
  if (result.ok) {
    const Eigen::Vector2d shape = result.camera.projection_params;
    result.description = StringPrintf(
        "sweep of %d candidates (focal %.3g to %.3g px, %zu shape value(s)) on %zu views: f = "
        "%.1f px, shape (%.3g, %.3g), median PnP RMS %.2f px",
        tried,
        kMinFocalWidths * width,
        kMaxFocalWidths * width,
        shapes.size(),
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
