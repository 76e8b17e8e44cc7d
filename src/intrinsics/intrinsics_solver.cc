#include "intrinsics_solver.h"

#include <ceres/manifold.h>

#include <algorithm>

#include "splinecal/intrinsics/rig_reprojection_cost.h"

namespace splinecal {
namespace internal {

PoseBlock ToBlock(const SE3d& pose) {
  PoseBlock block;
  PoseToBlock(pose, block.data());
  return block;
}

double InsetOf(const RigState& state, const TargetView& view) {
  const auto it = state.inset.find(view.t_ns);
  return it != state.inset.end() ? it->second : 0.0;
}

std::vector<TargetCornerObservation> ShapedCorners(const RigState& state,
                                                   const TargetView& view) {
  return DeformedCorners(view.corners, state.shape, state.deformation.data(), InsetOf(state, view));
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
  if (state_.shape.size() > 0) {
    problem_->AddParameterBlock(state_.deformation.data(), state_.shape.size());
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
    settings.shape = state_.shape;
    auto* cost = new RigViewCostFunction(settings, view.corners);
    std::vector<double*> blocks = {pose, state_.intrinsics[n].data()};
    if (n > 0) blocks.push_back(state_.T_cn_c0[n].data());
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
}

}  // namespace internal
}  // namespace splinecal
