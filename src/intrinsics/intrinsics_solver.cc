#include "intrinsics_solver.h"

#include <ceres/manifold.h>

#include <algorithm>

#include "splinecal/intrinsics/rig_reprojection_cost.h"
#include "splinecal/intrinsics/target_points_gauge.h"

namespace splinecal {
namespace internal {

PoseBlock ToBlock(const SE3d& pose) {
  PoseBlock block;
  PoseToBlock(pose, block.data());
  return block;
}

int PointOffsetTangentSize(const TargetShape& shape) {
  return shape.kind == TargetDeformationKind::kPointsInPlane ? 2 : 3;
}

double InsetOf(const RigState& state, const TargetView& view) {
  const auto it = state.inset.find(view.t_ns);
  return it != state.inset.end() ? it->second : 0.0;
}

std::vector<TargetCornerObservation> ShapedCorners(const RigState& state,
                                                   const TargetView& view) {
  if (!state.shape.per_point()) {
    return DeformedCorners(
        view.corners, state.shape, state.deformation.data(), InsetOf(state, view));
  }
  std::vector<TargetCornerObservation> moved = view.corners;
  for (size_t i = 0; i < moved.size(); ++i) {
    const auto it = state.point_offset.find(view.point_ids[i]);
    if (it != state.point_offset.end()) moved[i].p_t += Eigen::Vector3d(it->second.data());
  }
  return moved;
}

std::vector<const double*> IntrinsicsSolver::PointOffsetBlocks() const {
  std::vector<const double*> blocks;
  for (const auto& [id, offset] : state_.point_offset) blocks.push_back(offset.data());
  return blocks;
}

void IntrinsicsSolver::ChooseFreePoints() {
  std::map<int64_t, int> views_of;
  for (size_t v = 0; v < views_.size(); ++v) {
    if (records_[v].status != ViewStatus::kUsed) continue;
    for (int64_t id : views_[v].point_ids) ++views_of[id];
  }
  for (const auto& [id, count] : views_of) {
    if (count >= kMinViewsPerFreePoint) state_.point_offset[id] = {0.0, 0.0, 0.0};
  }
}

void IntrinsicsSolver::AddGauge() {
  std::vector<Eigen::Vector3d> points;
  std::vector<double*> blocks;
  for (auto& [id, offset] : state_.point_offset) {
    points.push_back(state_.file_points.at(id));
    blocks.push_back(offset.data());
  }
  if (blocks.empty()) return;
  problem_->AddResidualBlock(new TargetPointsGaugeCost(points), nullptr, blocks);
}

void IntrinsicsSolver::Build(double huber_px) {
  problem_ = std::make_unique<ceres::Problem>();
  view_of_.clear();
  const int num_cameras = static_cast<int>(state_.cameras.size());
  for (int n = 0; n < num_cameras; ++n) {
    problem_->AddParameterBlock(state_.intrinsics[n].data(), kNumIntrinsics);
    std::vector<int> fixed;
    for (int j = 0; j < kNumIntrinsics; ++j) {
      if (std::find(state_.active[n].begin(), state_.active[n].end(), j) ==
          state_.active[n].end()) {
        fixed.push_back(j);
      }
    }
    if (!fixed.empty()) {
      problem_->SetManifold(state_.intrinsics[n].data(),
                            new ceres::SubsetManifold(kNumIntrinsics, fixed));
    }
    if (n > 0) {
      problem_->AddParameterBlock(state_.T_cn_c0[n].data(), kPoseBlockSize, new SE3Manifold);
      if (!options_.estimate_extrinsics)
        problem_->SetParameterBlockConstant(state_.T_cn_c0[n].data());
    }
  }
  const bool per_point = state_.shape.per_point();
  if (per_point && state_.point_offset.empty()) ChooseFreePoints();
  if (state_.shape.size() > 0 && !per_point) {
    problem_->AddParameterBlock(state_.deformation.data(), state_.shape.size());
  }
  const bool z_held = PointOffsetTangentSize(state_.shape) == 2;
  for (auto& [id, offset] : state_.point_offset) {
    problem_->AddParameterBlock(offset.data(), 3);
    if (z_held) {
      problem_->SetManifold(offset.data(), new ceres::SubsetManifold(3, std::vector<int>{2}));
    }
  }
  for (size_t v = 0; v < views_.size(); ++v) {
    if (records_[v].status != ViewStatus::kUsed) continue;
    const TargetView& view = views_[v];
    const int n = view.cam_id;
    double* pose = state_.T_c0_t.at(view.t_ns).data();
    if (!problem_->HasParameterBlock(pose)) {
      problem_->AddParameterBlock(pose, kPoseBlockSize, new SE3Manifold);
    }
    RigViewOptions settings;
    settings.model = state_.cameras[n];
    settings.has_extrinsic = n > 0;
    settings.sigma_px = state_.sigma_px[n];
    settings.huber_px = huber_px;
    std::vector<double*> blocks = {pose, state_.intrinsics[n].data()};
    if (n > 0) blocks.push_back(state_.T_cn_c0[n].data());
    if (per_point) {
      // Each free point's corner alone with its offset block; the others in one block.
      std::vector<TargetCornerObservation> held;
      RigViewOptions free_settings = settings;
      free_settings.shape = state_.shape;
      for (size_t i = 0; i < view.corners.size(); ++i) {
        const auto it = state_.point_offset.find(view.point_ids[i]);
        if (it == state_.point_offset.end()) {
          held.push_back(view.corners[i]);
          continue;
        }
        std::vector<double*> corner_blocks = blocks;
        corner_blocks.push_back(it->second.data());
        const ceres::ResidualBlockId id = problem_->AddResidualBlock(
            new RigViewCostFunction(free_settings, {view.corners[i]}), nullptr, corner_blocks);
        view_of_[id] = &view;
      }
      if (!held.empty()) {
        const ceres::ResidualBlockId id = problem_->AddResidualBlock(
            new RigViewCostFunction(settings, std::move(held)), nullptr, blocks);
        view_of_[id] = &view;
      }
      continue;
    }
    settings.shape = state_.shape;
    auto* cost = new RigViewCostFunction(settings, view.corners);
    if (state_.shape.size() > 0) blocks.push_back(state_.deformation.data());
    if (state_.shape.per_view_inset()) {
      // std::map keeps the element's address: the block stays valid between rounds.
      double* inset = &state_.inset[view.t_ns];
      if (!problem_->HasParameterBlock(inset)) problem_->AddParameterBlock(inset, 1);
      blocks.push_back(inset);
    }
    const ceres::ResidualBlockId id = problem_->AddResidualBlock(cost, nullptr, blocks);
    view_of_[id] = &view;
  }
  if (per_point) AddGauge();
}

}  // namespace internal
}  // namespace splinecal
