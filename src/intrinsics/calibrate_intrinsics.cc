#include "splinecal/intrinsics/calibrate_intrinsics.h"

#include <ceres/manifold.h>
#include <ceres/problem.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <memory>
#include <set>
#include <unordered_map>

#include "splinecal/camera/observation_gates.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/pnp.h"
#include "splinecal/enum_names.h"
#include "splinecal/error.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/intrinsics/corner_outliers.h"
#include "splinecal/intrinsics/initial_intrinsics.h"
#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/intrinsics/rig_reprojection_cost.h"
#include "splinecal/intrinsics/robust_mean_pose.h"
#include "splinecal/intrinsics/target_points_check.h"
#include "splinecal/intrinsics/target_view.h"
#include "splinecal/intrinsics/time_blocks.h"
#include "splinecal/estimation/model_noise_cluster.h"
#include "splinecal/estimation/view_clusters.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/median.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"
#include "intrinsics_solver.h"

namespace splinecal {

namespace {

struct ViewStatusRow {
  ViewStatus value;
  const char* name;
  const char* key;
};

constexpr std::array<ViewStatusRow, 6> kViewStatusRows = {{
    {ViewStatus::kUsed, "used", "used"},
    {ViewStatus::kTooFewCorners, "too few corners", "too_few_corners"},
    {ViewStatus::kPnpFailed, "no target pose (PnP failed)", "pnp_failed"},
    {ViewStatus::kRepeat, "repeats an earlier view", "repeats"},
    {ViewStatus::kThinned, "thinned (max views)", "thinned"},
    {ViewStatus::kOutlier, "too few corners after outlier removal", "outlier"},
}};

}  // namespace

const char* ViewStatusName(ViewStatus status) { return NameOf(kViewStatusRows, status); }

const char* ViewStatusKey(ViewStatus status) { return RowOf(kViewStatusRows, status).key; }

namespace {

using internal::InsetOf;
using internal::IntrinsicsSolver;
using internal::PointOffsetTangentSize;
using internal::PoseBlock;
using internal::RigState;
using internal::ShapedCorners;
using internal::ToBlock;

SE3d PoseOf(const PoseBlock& block) { return PoseFromBlock(block.data()); }

Camera CameraAt(const RigState& state, int n) {
  Camera camera = state.cameras[n];
  camera.set_intrinsics(state.intrinsics[n]);
  return camera;
}

SE3d TargetInCamera(const RigState& state, const TargetView& view) {
  const SE3d T_c0_t = PoseOf(state.T_c0_t.at(view.t_ns));
  return view.cam_id == 0 ? T_c0_t : PoseOf(state.T_cn_c0[view.cam_id]) * T_c0_t;
}

// Distance between two target poses for the repeat test: rotation angle [deg] and the position
// difference relative to the distance.
bool IsRepeat(const SE3d& a, const SE3d& b, const IntrinsicsOptions& options) {
  const double angle_deg = (a.so3().inverse() * b.so3()).Log().norm() * 180.0 / kPi;
  if (angle_deg > options.duplicate_rotation_deg) return false;
  const double distance = std::max(a.translation().norm(), 1e-9);
  return (a.translation() - b.translation()).norm() <= options.duplicate_distance_ratio * distance;
}

// Steps 2-3 for camera n: initial intrinsics, PnP per view, repeats and thinning.
void InitialiseCamera(int n,
                      const IntrinsicsCameraSpec& spec,
                      std::vector<TargetView>* views,
                      std::vector<ViewRecord>* records,
                      const IntrinsicsOptions& options,
                      RigState* state,
                      std::string* description,
                      std::vector<std::string>* warnings) {
  std::vector<const TargetView*> candidates;
  for (size_t v = 0; v < views->size(); ++v) {
    if ((*views)[v].cam_id == n && (*records)[v].status == ViewStatus::kUsed) {
      candidates.push_back(&(*views)[v]);
    }
  }
  if (candidates.empty()) {
    throw Error(
        StringPrintf("cam%d: no view with at least %d target corners: nothing to "
                     "calibrate it from",
                     n,
                     options.min_corners));
  }
  Camera camera = spec.camera;
  if (spec.initial_values) {
    *description = "from the given camchain";
  } else {
    const InitialIntrinsics initial = InitialiseIntrinsics(spec.camera, candidates);
    if (!initial.ok) {
      throw Error(StringPrintf("cam%d (%s): no starting point found: %s",
                               n,
                               CameraModelName(camera.projection, camera.distortion).c_str(),
                               initial.description.c_str()));
    }
    camera = initial.camera;
    *description = initial.description;
    if (!initial.warning.empty()) {
      warnings->push_back(StringPrintf("cam%d (%s): %s",
                                       n,
                                       CameraModelName(camera.projection, camera.distortion).c_str(),
                                       initial.warning.c_str()));
    }
  }
  state->cameras[n] = camera;
  state->intrinsics[n] = camera.intrinsics();
  state->active[n] = camera.ActiveIntrinsics();

  std::vector<double> rms;
  std::vector<double> view_rms(views->size(), 0.0);
  for (size_t v = 0; v < views->size(); ++v) {
    TargetView& view = (*views)[v];
    if (view.cam_id != n || (*records)[v].status != ViewStatus::kUsed) continue;
    std::vector<Eigen::Vector3d> p_t;
    std::vector<Eigen::Vector2d> uv;
    for (const TargetCornerObservation& c : view.corners) {
      p_t.push_back(c.p_t);
      uv.push_back(c.uv);
    }
    const PnpResult pnp = SolvePnp(camera, p_t, uv);
    view.pnp_ok = pnp.ok;
    view.T_c_t = pnp.T_c_t;
    if (pnp.ok) {
      rms.push_back(pnp.rms_px);
      view_rms[v] = pnp.rms_px;
    } else {
      (*records)[v].status = ViewStatus::kPnpFailed;
    }
  }
  // A PnP pose far worse than the typical view (a flipped planar pose, a mislabelled corner)
  // would start the solve in the wrong basin.
  const double rms_limit = std::max(10.0, 10.0 * Median(rms));
  std::vector<size_t> kept;
  for (size_t v = 0; v < views->size(); ++v) {
    const TargetView& view = (*views)[v];
    if (view.cam_id != n || (*records)[v].status != ViewStatus::kUsed) continue;
    if (view_rms[v] > rms_limit) {
      (*records)[v].status = ViewStatus::kPnpFailed;
      continue;
    }
    bool repeat = false;
    for (size_t i = 0; i < kept.size() && !options.keep_repeated_views && !repeat; ++i) {
      repeat = IsRepeat(view.T_c_t, (*views)[kept[i]].T_c_t, options);
    }
    if (repeat) {
      (*records)[v].status = ViewStatus::kRepeat;
    } else {
      kept.push_back(v);
    }
  }
  const size_t max_views = static_cast<size_t>(options.max_views_per_camera);
  if (max_views > 0 && kept.size() > max_views) {
    std::set<size_t> keep;
    for (size_t i = 0; i < max_views; ++i) keep.insert(kept[i * kept.size() / max_views]);
    for (size_t v : kept) {
      if (keep.count(v) == 0) (*records)[v].status = ViewStatus::kThinned;
    }
  }
}

// Step 4: T_cn_c0 of every camera from shared timestamps (or as given), then T_c0_t per time.
void PlaceRig(const std::vector<TargetView>& views,
              std::vector<ViewRecord>* records,
              const IntrinsicsOptions& options,
              RigState* state,
              std::vector<bool>* extrinsic_estimated) {
  const int num_cameras = static_cast<int>(state->cameras.size());
  std::vector<bool> placed(num_cameras, false);
  placed[0] = true;
  state->T_cn_c0.assign(num_cameras, ToBlock(SE3d()));
  extrinsic_estimated->assign(num_cameras, false);
  if (!options.estimate_extrinsics) {
    for (int n = 0; n < num_cameras; ++n) state->T_cn_c0[n] = ToBlock(options.T_cn_c0_given[n]);
    placed.assign(num_cameras, true);
  }
  // Used views by timestamp.
  std::map<int64_t, std::vector<size_t>> by_time;
  for (size_t v = 0; v < views.size(); ++v) {
    if ((*records)[v].status == ViewStatus::kUsed) by_time[views[v].t_ns].push_back(v);
  }
  bool progress = true;
  while (progress) {
    progress = false;
    for (int n = 1; n < num_cameras; ++n) {
      if (placed[n]) continue;
      std::vector<SE3d> candidates;
      for (const auto& [t, list] : by_time) {
        const TargetView* own = nullptr;
        const TargetView* other = nullptr;
        for (size_t v : list) {
          if (views[v].cam_id == n) own = &views[v];
          if (placed[views[v].cam_id] && (other == nullptr || views[v].cam_id == 0)) {
            other = &views[v];
          }
        }
        if (own == nullptr || other == nullptr) continue;
        // T_cn_c0 = T_cn_t T_cm_t^-1 T_cm_c0.
        candidates.push_back(own->T_c_t * other->T_c_t.inverse() *
                             PoseOf(state->T_cn_c0[other->cam_id]));
      }
      if (candidates.empty()) continue;
      state->T_cn_c0[n] = ToBlock(RobustMeanPose(candidates));
      placed[n] = true;
      (*extrinsic_estimated)[n] = true;
      progress = true;
    }
  }
  for (int n = 1; n < num_cameras; ++n) {
    if (!placed[n]) {
      throw Error(StringPrintf(
          "cam%d never sees the target at the same timestamp as another camera: its pose in "
          "the rig cannot be found (are the cameras' timestamps synchronised?)",
          n));
    }
  }
  // T_c0_t per timestamp: camera 0's own view, else the first camera's through the rig.
  state->T_c0_t.clear();
  for (const auto& [t, list] : by_time) {
    const TargetView* best = &views[list.front()];
    for (size_t v : list) {
      if (views[v].cam_id == 0) best = &views[v];
    }
    state->T_c0_t[t] = ToBlock(PoseOf(state->T_cn_c0[best->cam_id]).inverse() * best->T_c_t);
  }
}

// Step 5's outlier pass (intrinsics/corner_outliers.h): per camera the corners far beyond the
// robust scale of their view and of their image cell go, and views left with too few corners;
// sigma_px is the camera-wide robust scale. The removed corners go to *removed (their errors at
// the solution they were removed from), a warning when they are many.
void RejectOutliers(const IntrinsicsOptions& options,
                    std::vector<TargetView>* views,
                    std::vector<ViewRecord>* records,
                    RigState* state,
                    std::vector<ReprojectionSample>* removed,
                    std::vector<std::string>* warnings) {
  const int num_cameras = static_cast<int>(state->cameras.size());
  for (int n = 0; n < num_cameras; ++n) {
    std::vector<size_t> indices;
    std::vector<ViewErrors> errors;
    for (size_t v = 0; v < views->size(); ++v) {
      if ((*records)[v].status != ViewStatus::kUsed || (*views)[v].cam_id != n) continue;
      const TargetView& view = (*views)[v];
      indices.push_back(v);
      ViewErrors& e = errors.emplace_back();
      e.error = RigViewErrors(
          CameraAt(*state, n), TargetInCamera(*state, view), ShapedCorners(*state, view));
      for (const TargetCornerObservation& c : view.corners) {
        e.uv.push_back(c.uv);
        e.p_t.push_back(c.p_t);
      }
    }
    const Camera& camera = state->cameras[n];
    const CornerOutliers outliers =
        FindCornerOutliers(errors, camera.width, camera.height, options.outlier_sigmas);
    state->sigma_px[n] = outliers.sigma_px;
    const std::string warning = CornerOutlierWarning(
        StringPrintf("cam%d", n), CameraModelName(camera.projection, camera.distortion), outliers);
    if (!warning.empty()) warnings->push_back(warning);
    for (size_t k = 0; k < indices.size(); ++k) {
      const size_t v = indices[k];
      TargetView& view = (*views)[v];
      TargetView kept = view;
      kept.corners.clear();
      kept.point_ids.clear();
      for (size_t i = 0; i < view.corners.size(); ++i) {
        if (!outliers.outlier[k][i]) {
          kept.corners.push_back(view.corners[i]);
          kept.point_ids.push_back(view.point_ids[i]);
          continue;
        }
        ++(*records)[v].corners_rejected;
        removed->push_back(
            {view.t_ns, n, view.point_ids[i], view.corners[i].uv, errors[k].error[i]});
      }
      view = std::move(kept);
      if (static_cast<int>(view.corners.size()) < options.min_corners) {
        (*records)[v].status = ViewStatus::kOutlier;
      }
    }
  }
}

// The noise level the final residuals show, per camera: sqrt(sum e^2 / (m - p)) with m error
// components and p the parameters they determine (the camera's active intrinsics, 6 per view
// pose, shared poses split between the cameras seeing them, the extrinsic).
void MeasureSigma(const std::vector<TargetView>& views,
                  const std::vector<ViewRecord>& records,
                  RigState* state) {
  const int num_cameras = static_cast<int>(state->cameras.size());
  std::map<int64_t, int> cameras_at;
  for (size_t v = 0; v < views.size(); ++v) {
    if (records[v].status == ViewStatus::kUsed) ++cameras_at[views[v].t_ns];
  }
  std::vector<double> sum(num_cameras, 0.0), m(num_cameras, 0.0), p(num_cameras, 0.0);
  for (int n = 0; n < num_cameras; ++n) {
    p[n] = static_cast<double>(state->active[n].size()) + (n > 0 ? 6.0 : 0.0);
  }
  for (size_t v = 0; v < views.size(); ++v) {
    if (records[v].status != ViewStatus::kUsed) continue;
    const TargetView& view = views[v];
    for (const Eigen::Vector2d& e : RigViewErrors(CameraAt(*state, view.cam_id),
                                                  TargetInCamera(*state, view),
                                                  ShapedCorners(*state, view))) {
      if (!e.allFinite()) continue;
      sum[view.cam_id] += e.squaredNorm();
      m[view.cam_id] += 2.0;
    }
    p[view.cam_id] += 6.0 / cameras_at[view.t_ns];
  }
  for (int n = 0; n < num_cameras; ++n) {
    if (m[n] > p[n]) state->sigma_px[n] = std::max(std::sqrt(sum[n] / (m[n] - p[n])), 1e-6);
  }
}

SolveRounds MakeSolveRounds(const IntrinsicsOptions& options,
                            double jacobian_entries,
                            bool every_point_free) {
  SolverOptions solver = options.solver;
  // The target poses form an independent set: the Schur complement leaves the intrinsics, the
  // extrinsics and the target's shape. A few dozen coordinates, sparse in Ceres' block sense;
  // with every point free each view couples its ~100 points' offsets with each other and the
  // intrinsics, and the reduced system of ~1300 coordinates is dense (on EuRoC's imu_april
  // 14.7 s of solving as sparse, 8.6 s as dense; the default's 1.8 s gain nothing from it).
  if (solver.linear_solver == LinearSolver::kAuto) {
    solver.linear_solver = every_point_free ? LinearSolver::kDenseSchur : LinearSolver::kSparseSchur;
  }
  return SolveRounds(solver, jacobian_entries);
}

void CheckSolve(const SolveRounds& rounds) {
  if (rounds.failed()) {
    throw Error("intrinsics: the solver failed: " + rounds.last().message);
  }
}

// Each timestamp's score on the active intrinsics, J^T r of its views' weighted residuals
// (time_blocks.h), for the autocorrelation that chooses the covariance's time blocks.
void TimestampScores(IntrinsicsSolver* solver,
                     const RigState& state,
                     const std::vector<int>& offset,
                     int size,
                     std::vector<double>* t_s,
                     std::vector<Eigen::VectorXd>* scores) {
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  ceres::Problem* problem = solver->problem();
  std::vector<ceres::ResidualBlockId> ids;
  problem->GetResidualBlocks(&ids);
  std::map<int64_t, Eigen::VectorXd> by_time;
  for (ceres::ResidualBlockId id : ids) {
    const ceres::CostFunction* cost = problem->GetCostFunctionForResidualBlock(id);
    std::vector<double*> blocks;
    problem->GetParameterBlocksForResidualBlock(id, &blocks);
    const int rows = cost->num_residuals();
    Eigen::VectorXd r(rows);
    RowMajor J(rows, kNumIntrinsics);
    std::vector<double*> jacobians(blocks.size(), nullptr);
    jacobians[1] = J.data();  // (target pose, intrinsics[, extrinsic])
    const TargetView* view = solver->ViewOf(id);
    if (view == nullptr) continue;  // the free points' gauge: no intrinsics
    if (!cost->Evaluate(blocks.data(), r.data(), jacobians.data())) continue;
    Eigen::VectorXd& score =
        by_time.try_emplace(view->t_ns, Eigen::VectorXd::Zero(size)).first->second;
    const std::vector<int>& active = state.active[view->cam_id];
    for (size_t j = 0; j < active.size(); ++j) {
      score(offset[view->cam_id] + static_cast<int>(j)) += J.col(active[j]).dot(r);
    }
  }
  for (const auto& [t, score] : by_time) {
    t_s->push_back(NanosecondsToSeconds(t - by_time.begin()->first));
    scores->push_back(score);
  }
}

// The target's shape and, with a covariance, its std (its block at `offset` in `covariance`;
// every point free: the free points' offsets there, in id order).
void FillDeformationResult(const RigState& state,
                           const Eigen::MatrixXd& covariance,
                           int offset,
                           IntrinsicsResult* result) {
  const int k = state.shape.size();
  if (k == 0) return;
  TargetDeformationResult& out = result->target_deformation;
  if (state.shape.per_point()) {
    out.refined_target.type = "points";
    out.refined_target.points = state.file_points;
    const int tangent = PointOffsetTangentSize(state.shape);
    if (covariance.size() > 0) {
      // Every offset's coordinates in id order (x, y, z; z absent when held).
      const int rows = tangent * static_cast<int>(state.point_offset.size());
      out.covariance = covariance.block(offset, offset, rows, rows);
    }
    int row = offset;
    for (const auto& [id, block] : state.point_offset) {
      const Eigen::Vector3d c(block.data());
      out.point_offsets_m[id] = c;
      out.refined_target.points[id] += c;
      if (covariance.size() > 0) {
        Eigen::Vector3d std = Eigen::Vector3d::Zero();  // a held z: 0
        std.head(tangent) = covariance.block(row, row, tangent, tangent).diagonal().cwiseSqrt();
        out.point_offsets_std_m[id] = std;
      }
      row += tangent;
    }
    return;
  }
  out.coefficients = Eigen::Map<const Eigen::VectorXd>(state.deformation.data(), k);
  out.heights_m = out.heights.M * out.coefficients;
  out.view_inset = state.inset;
  if (covariance.size() == 0) return;
  out.covariance = covariance.block(offset, offset, k, k);
  out.heights_std_m =
      (out.heights.M * out.covariance * out.heights.M.transpose()).diagonal().cwiseSqrt();
}

// Steps 6 (covariance) and the per-camera results.
void FillCameraResults(IntrinsicsSolver* solver,
                       const IntrinsicsOptions& options,
                       const std::vector<bool>& extrinsic_estimated,
                       RigState* state,
                       IntrinsicsResult* result) {
  const int num_cameras = static_cast<int>(state->cameras.size());
  std::vector<const double*> blocks;
  std::vector<int> offset_intrinsics(num_cameras, -1), offset_extrinsic(num_cameras, -1);
  int size = 0;
  for (int n = 0; n < num_cameras; ++n) {
    offset_intrinsics[n] = size;
    blocks.push_back(state->intrinsics[n].data());
    size += static_cast<int>(state->active[n].size());
    if (n > 0 && options.estimate_extrinsics) {
      offset_extrinsic[n] = size;
      blocks.push_back(state->T_cn_c0[n].data());
      size += 6;
    }
  }
  // The time blocks are chosen from the cameras' intrinsics alone, with or without a shape.
  const int scores_size = size;
  const int offset_shape = size;
  if (state->shape.per_point()) {
    for (const double* offset : solver->PointOffsetBlocks()) {
      blocks.push_back(offset);
      size += PointOffsetTangentSize(state->shape);
    }
  } else if (state->shape.size() > 0) {
    blocks.push_back(state->deformation.data());
    size += state->shape.size();
  }
  Eigen::MatrixXd covariance;
  // Per coordinate: where its std comes from (the names result.yaml's std_from uses).
  std::vector<const char*> source(size, "noise");
  if (options.covariance.compute) {
    MarginalCovarianceOptions cov_options;
    cov_options.backend = options.covariance.backend;
    cov_options.max_ceres_covariance_entries = options.covariance.max_ceres_covariance_entries;
    cov_options.num_threads = options.solver.num_threads;
    const bool robust = options.covariance.robust_window_s > 0.0;
    if (robust) {
      std::vector<double> t_s;
      std::vector<Eigen::VectorXd> scores;
      TimestampScores(solver, *state, offset_intrinsics, scores_size, &t_s, &scores);
      result->time_blocks = ChooseTimeBlocks(t_s, scores);
      const int64_t t0_ns = state->T_c0_t.begin()->first;
      const double block_s = result->time_blocks.block_s;
      if (block_s > 0.0) {
        cov_options.cluster_of = [solver, t0_ns, block_s](ceres::ResidualBlockId id) {
          const TargetView* view = solver->ViewOf(id);
          // The free points' gauge holds what no data determines: a constraint, not data.
          if (view == nullptr) return kModelNoiseCluster;
          return static_cast<int>(NanosecondsToSeconds(view->t_ns - t0_ns) / block_s);
        };
      }
    }
    // The second sandwich, over kinds of view (view_clusters.h), from the same linearisation as
    // the time blocks' (or alone when the recording is too short for time blocks); each std is
    // the larger. A view's cluster once, not once per residual block (with every point free a
    // view has one per corner).
    const bool time_blocks = static_cast<bool>(cov_options.cluster_of);
    const bool view_clusters = robust && options.covariance.view_clusters;
    if (view_clusters) {
      const RigState* rig = state;
      auto cluster_of_view = std::make_shared<std::unordered_map<const TargetView*, int>>();
      auto by_view = [solver, rig, cluster_of_view](ceres::ResidualBlockId id) {
        const TargetView* view = solver->ViewOf(id);
        if (view == nullptr) return kModelNoiseCluster;
        const auto [it, added] = cluster_of_view->emplace(view, 0);
        if (added) {
          it->second =
              ViewCluster(rig->cameras[view->cam_id], view->corners, TargetInCamera(*rig, *view));
        }
        return it->second;
      };
      if (time_blocks) {
        cov_options.further_cluster_of.push_back(by_view);
      } else {
        cov_options.cluster_of = by_view;
      }
    }
    MarginalCovariance marginal = ComputeMarginalCovariance(solver->problem(), blocks, cov_options);
    if (marginal.ok) {
      MarginalCovariance by_view_kind;
      if (view_clusters && !time_blocks) {
        std::swap(by_view_kind.robust_covariance, marginal.robust_covariance);
        std::swap(by_view_kind.num_clusters, marginal.num_clusters);
        by_view_kind.ok = true;
        by_view_kind.covariance = marginal.covariance;
        by_view_kind.noise_covariance = marginal.noise_covariance;
      } else if (view_clusters && !marginal.further.empty()) {
        by_view_kind = std::move(marginal.further.front());
      }
      const ReportedCovariance by_time = ReportedCovarianceOf(marginal);
      result->time_blocks_count = marginal.num_clusters;
      Eigen::VectorXd inflation = by_time.inflation;
      for (int i = 0; i < size; ++i) {
        if (inflation(i) > 1.0 + 1e-9) source[i] = "time blocks";
      }
      if (view_clusters) {
        result->view_clusters_count = by_view_kind.num_clusters;
        if (by_view_kind.ok && by_view_kind.num_clusters >= kMinViewClusters) {
          const ReportedCovariance by_view = ReportedCovarianceOf(by_view_kind);
          for (int i = 0; i < size; ++i) {
            if (by_view.inflation(i) > inflation(i) && by_view.inflation(i) > 1.0 + 1e-9) {
              inflation(i) = by_view.inflation(i);
              source[i] = "view clusters";
            }
          }
        }
      }
      // Rows and columns scaled alike: the correlations stay the noise model's.
      covariance = inflation.asDiagonal() * marginal.covariance * inflation.asDiagonal();
    } else {
      result->warnings.push_back(
          "the intrinsics are not all determined (singular information): no standard deviations");
    }
  }
  FillDeformationResult(*state, covariance, offset_shape, result);
  for (int n = 0; n < num_cameras; ++n) {
    IntrinsicsCameraResult& camera = result->cameras[n];
    camera.camera = CameraAt(*state, n);
    camera.active = state->active[n];
    camera.pixel_sigma_px = state->sigma_px[n];
    camera.extrinsic_estimated = n > 0 && options.estimate_extrinsics && extrinsic_estimated[n];
    camera.T_cn_c0 = PoseOf(state->T_cn_c0[n]);
    if (n > 0) camera.T_cn_cnm1 = camera.T_cn_c0 * PoseOf(state->T_cn_c0[n - 1]).inverse();
    if (covariance.size() == 0) continue;
    const int k = static_cast<int>(camera.active.size());
    camera.intrinsics_covariance =
        covariance.block(offset_intrinsics[n], offset_intrinsics[n], k, k);
    for (int j = 0; j < k; ++j) {
      camera.intrinsics_std(camera.active[j]) = std::sqrt(camera.intrinsics_covariance(j, j));
    }
    // The full covariance for camchain.yaml: the active intrinsics in Kalibr's order, then
    // T_cn_cnm1's right tangent [rho; phi], as rows D of the solved coordinates.
    std::vector<int> rows;
    for (const std::vector<int>& order :
         {KalibrIntrinsicsOrder(camera.camera), KalibrDistortionOrder(camera.camera)}) {
      for (int index : order) {
        const auto found = std::find(camera.active.begin(), camera.active.end(), index);
        if (found == camera.active.end()) continue;
        rows.push_back(offset_intrinsics[n] + static_cast<int>(found - camera.active.begin()));
        camera.covariance.parameters.push_back(IntrinsicName(camera.camera, index));
        camera.std_from.push_back(source[rows.back()]);
      }
    }
    const bool with_extrinsic = n > 0 && offset_extrinsic[n] >= 0;
    Eigen::MatrixXd D = Eigen::MatrixXd::Zero(rows.size() + (with_extrinsic ? 6 : 0), size);
    for (size_t r = 0; r < rows.size(); ++r) D(r, rows[r]) = 1.0;
    if (with_extrinsic) {
      // T_cn_c0 Exp(a), T_cnm1_c0 Exp(b): T_cn_cnm1 Exp(Ad(T_cnm1_c0) (a - b)) to first order.
      Eigen::MatrixXd E = Eigen::MatrixXd::Zero(6, size);
      E.block<6, 6>(0, offset_extrinsic[n]).setIdentity();
      if (n > 1)
        E.block<6, 6>(0, offset_extrinsic[n - 1]) = -Eigen::Matrix<double, 6, 6>::Identity();
      D.bottomRows(6) = PoseOf(state->T_cn_c0[n - 1]).Adj() * E;
      for (const char* axis : {"rho_x", "rho_y", "rho_z", "phi_x", "phi_y", "phi_z"}) {
        camera.covariance.parameters.push_back(std::string("T_cn_cnm1_") + axis);
      }
    }
    camera.covariance.matrix = D * covariance * D.transpose();
    camera.covariance.block_seconds = result->time_blocks.block_s;
    if (with_extrinsic) {
      camera.T_cn_cnm1_std =
          camera.covariance.matrix.bottomRightCorner(6, 6).diagonal().cwiseSqrt();
    }
  }
}

}  // namespace

IntrinsicsResult CalibrateIntrinsics(const std::vector<Observation>& observations,
                                     const CalibrationTarget& target,
                                     const std::vector<IntrinsicsCameraSpec>& cameras,
                                     const IntrinsicsOptions& options) {
  const int num_cameras = static_cast<int>(cameras.size());
  if (num_cameras == 0) throw Error("intrinsics: no camera to calibrate");
  if (!options.estimate_extrinsics &&
      static_cast<int>(options.T_cn_c0_given.size()) != num_cameras) {
    throw Error("intrinsics: held extrinsics need one T_cn_c0 per camera");
  }
  CheckSolverOptions(options.solver);
  std::vector<Camera> given_cameras;  // the target's layout and the image sizes
  for (const IntrinsicsCameraSpec& spec : cameras) given_cameras.push_back(spec.camera);
  CheckObservationInputs(observations, &target, given_cameras);
  int64_t unknown_ids = 0;
  std::vector<TargetView> views = MakeTargetViews(observations, target, &unknown_ids);
  IntrinsicsResult result;
  if (unknown_ids > 0) {
    result.warnings.push_back(StringPrintf(
        "%lld observation(s) name a point id the target does not have; they are not used",
        static_cast<long long>(unknown_ids)));
  }
  std::vector<ViewRecord> records(views.size());
  for (size_t v = 0; v < views.size(); ++v) {
    if (views[v].cam_id < 0 || views[v].cam_id >= num_cameras) {
      throw Error(
          StringPrintf("observations of cam_id %d but %d camera model(s) given: one "
                       "model per camera, cam0 first",
                       views[v].cam_id,
                       num_cameras));
    }
    records[v].t_ns = views[v].t_ns;
    records[v].cam_id = views[v].cam_id;
    records[v].corners = static_cast<int>(views[v].corners.size());
    if (records[v].corners < options.min_corners) records[v].status = ViewStatus::kTooFewCorners;
  }

  RigState state;
  state.shape = MakeTargetShape(target, options.target_deformation);
  if (state.shape.per_point()) state.file_points = target.points;
  result.target_deformation.shape = state.shape;
  if (state.shape.size() > 0) {
    result.target_deformation.heights = MakeTargetDeformationHeights(target, state.shape);
  }
  state.cameras.resize(num_cameras);
  state.intrinsics.resize(num_cameras);
  state.active.resize(num_cameras);
  state.sigma_px.assign(num_cameras, 1.0);
  result.cameras.resize(num_cameras);
  for (int n = 0; n < num_cameras; ++n) {
    InitialiseCamera(n,
                     cameras[n],
                     &views,
                     &records,
                     options,
                     &state,
                     &result.cameras[n].initialisation,
                     &result.warnings);
  }
  std::vector<bool> extrinsic_estimated;
  PlaceRig(views, &records, options, &state, &extrinsic_estimated);

  IntrinsicsSolver solver(&views, &records, &state, options);
  double jacobian_entries = 0.0;
  for (const TargetView& view : views) jacobian_entries += 2.0 * view.corners.size() * 13;
  SolveRounds rounds = MakeSolveRounds(options, jacobian_entries, state.shape.per_point());
  solver.Build(options.huber_px);
  rounds.Solve(solver.problem(), "intrinsics, robust: ");
  CheckSolve(rounds);
  RejectOutliers(options, &views, &records, &state, &result.removed_corners, &result.warnings);
  solver.Build(0.0);
  rounds.Solve(solver.problem(), "intrinsics: ");
  CheckSolve(rounds);
  const std::vector<double> sigma_before = state.sigma_px;
  MeasureSigma(views, records, &state);
  solver.Build(0.0);
  bool changed = false;
  for (int n = 0; n < num_cameras; ++n) {
    changed = changed || std::abs(state.sigma_px[n] / sigma_before[n] - 1.0) > 0.05;
  }
  // One camera: the weights' scale does not move the solution. Several: their ratio does.
  if (changed && num_cameras > 1) {
    rounds.Solve(solver.problem(), "intrinsics, measured noise: ");
    CheckSolve(rounds);
  }
  result.solve = rounds.Summary();
  if (!rounds.NoConvergenceWarning().empty()) {
    result.warnings.push_back("intrinsics: " + rounds.NoConvergenceWarning());
  }
  FillCameraResults(&solver, options, extrinsic_estimated, &state, &result);

  // Residuals, per-view RMS, counts, observability.
  std::vector<std::vector<const TargetView*>> used(num_cameras);
  std::vector<double> sum_sq(num_cameras, 0.0);
  std::vector<TargetPointsCheckView> check_views;  // with the file's layout only
  for (size_t v = 0; v < views.size(); ++v) {
    ViewRecord& record = records[v];
    IntrinsicsCameraResult& camera = result.cameras[record.cam_id];
    ++camera.views_offered;
    camera.corners_rejected += record.corners_rejected;
    if (record.status != ViewStatus::kUsed) continue;
    const TargetView& view = views[v];
    ++camera.views_used;
    const std::vector<Eigen::Vector2d> errors =
        RigViewErrors(camera.camera, TargetInCamera(state, view), ShapedCorners(state, view));
    double view_sq = 0.0;
    int count = 0;
    for (size_t i = 0; i < errors.size(); ++i) {
      if (!errors[i].allFinite()) continue;
      result.residuals.push_back(
          {view.t_ns, view.cam_id, view.point_ids[i], view.corners[i].uv, errors[i]});
      view_sq += errors[i].squaredNorm();
      ++count;
    }
    camera.corners_used += count;
    sum_sq[view.cam_id] += view_sq;
    record.rms_px = count > 0 ? std::sqrt(view_sq / count) : 0.0;
    TargetView& final_view = views[v];
    final_view.T_c_t = TargetInCamera(state, view);
    used[view.cam_id].push_back(&final_view);
    if (options.target_deformation == TargetDeformationKind::kNone) {
      check_views.push_back({camera.camera, final_view.T_c_t, &final_view,
                             state.sigma_px[view.cam_id]});
    }
  }
  if (!check_views.empty()) {
    result.target_points_check = CheckTargetPoints(check_views, kMinViewsPerFreePoint);
    const std::string warning = TargetPointsWarning(result.target_points_check);
    if (!warning.empty()) result.warnings.push_back(warning);
  }
  for (int n = 0; n < num_cameras; ++n) {
    IntrinsicsCameraResult& camera = result.cameras[n];
    camera.reprojection_rms_px =
        camera.corners_used > 0 ? std::sqrt(sum_sq[n] / camera.corners_used) : 0.0;
    const IntrinsicsObservability observability = AnalyseObservability(
        StringPrintf("cam%d (%s)",
                     n,
                     CameraModelName(camera.camera.projection, camera.camera.distortion).c_str()),
        camera.camera,
        camera.active,
        used[n],
        state.sigma_px[n]);
    if (!observability.warning.empty()) result.warnings.push_back(observability.warning);
  }
  // Timestamps whose views all went in the outlier pass keep their pose out of the result.
  std::set<int64_t> used_times;
  for (size_t v = 0; v < views.size(); ++v) {
    if (records[v].status == ViewStatus::kUsed) used_times.insert(views[v].t_ns);
  }
  for (const auto& [t, block] : state.T_c0_t) {
    if (used_times.count(t) > 0) result.target_poses.emplace_back(t, PoseOf(block));
  }
  result.views = std::move(records);
  return result;
}

}  // namespace splinecal
