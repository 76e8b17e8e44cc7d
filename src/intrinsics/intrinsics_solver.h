// The intrinsics solve's state and its Ceres problem (private to src/intrinsics/, the steps in
// calibrate_intrinsics.h): what the rounds change, kept between them, and the problem built over
// the used views from it.
#ifndef SPLINECAL_SRC_INTRINSICS_INTRINSICS_SOLVER_H_
#define SPLINECAL_SRC_INTRINSICS_INTRINSICS_SOLVER_H_

#include <ceres/problem.h>

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <map>
#include <memory>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/intrinsics/target_view.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace internal {

using PoseBlock = std::array<double, kPoseBlockSize>;

// A pose as its Ceres parameter block (lie/se3_manifold.h's layout).
PoseBlock ToBlock(const SE3d& pose);

// Everything the solve changes, kept between rounds.
struct RigState {
  std::vector<Camera> cameras;
  std::vector<IntrinsicsVector> intrinsics;  // parameter blocks
  std::vector<std::vector<int>> active;
  std::vector<PoseBlock> T_cn_c0;  // parameter blocks (camera 0: identity, unused)
  std::vector<double> sigma_px;
  std::map<int64_t, PoseBlock> T_c0_t;  // per timestamp with a used view
  TargetShape shape;                    // kind none: a flat target
  std::array<double, kMaxTargetDeformationSize> deformation{};  // its block (shape.size() used)
  std::map<int64_t, double> inset;  // with a per-view inset: d_v per timestamp (1-blocks)
  // With every point free: every point of the target file, and the free ones' offsets (3-blocks;
  // a point seen in fewer than kMinViewsPerFreePoint used views has none and keeps the file's
  // position).
  std::map<int64_t, Eigen::Vector3d> file_points;
  std::map<int64_t, std::array<double, 3>> point_offset;
};


// A free point's offset block's tangent: x, y, z, or x, y with z held (points-in-plane).
int PointOffsetTangentSize(const TargetShape& shape);

// The view's inset d_v (0 before its block exists or without a per-view inset).
double InsetOf(const RigState& state, const TargetView& view);
// The view's corners on the target as the state shapes it (flat: as they are; every point free:
// each moved by its offset).
std::vector<TargetCornerObservation> ShapedCorners(const RigState& state,
                                                   const TargetView& view);

// The Ceres problem over the used views: each view one RigViewCostFunction on the state's
// blocks (its target pose, its camera's intrinsics, its camera's extrinsic, the target's shape
// and per-view inset when estimated). With every point free, each corner of a free point is a
// residual block of its own with the point's offset block (the view's other corners share one),
// and the offsets' gauge (intrinsics/target_points_gauge.h) is one more residual block.
class IntrinsicsSolver {
 public:
  IntrinsicsSolver(std::vector<TargetView>* views,
                   std::vector<ViewRecord>* records,
                   RigState* state,
                   const IntrinsicsOptions& options)
      : views_(*views), records_(*records), state_(*state), options_(options) {}

  // Builds the problem over the used views with Huber at huber_px (0: none). With every point
  // free, a call before any is chosen chooses the free points (those in kMinViewsPerFreePoint
  // used views).
  void Build(double huber_px);

  ceres::Problem* problem() { return problem_.get(); }
  // The view a residual block holds; nullptr for the free points' gauge.
  const TargetView* ViewOf(ceres::ResidualBlockId id) const {
    const auto it = view_of_.find(id);
    return it == view_of_.end() ? nullptr : it->second;
  }
  // The free points' offset blocks, in id order (empty unless every point is free).
  std::vector<const double*> PointOffsetBlocks() const;

 private:
  std::vector<TargetView>& views_;
  std::vector<ViewRecord>& records_;
  RigState& state_;
  const IntrinsicsOptions& options_;
  std::unique_ptr<ceres::Problem> problem_;
  std::map<ceres::ResidualBlockId, const TargetView*> view_of_;

  void ChooseFreePoints();
  void AddGauge();
};

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_INTRINSICS_INTRINSICS_SOLVER_H_
