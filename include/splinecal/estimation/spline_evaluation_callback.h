// Per-iteration sharing of the spline's knot work between residuals (`splinecal fit`).
//
// Every IMU and pose residual of a segment needs the same three knot deltas
// Omega_k = Log(T_{k-1}^-1 T_k) and their Jacobians Jr^-1(Omega_k), Jl^-1(Omega_k)
// (spline/segment.h, KnotDelta / KnotDeltaJacobians). Computed per residual, a knot's work would
// be repeated by the ~40 residuals that touch it (20 IMU samples per segment at 200 Hz and
// dt = 0.1 s, three segments per knot); here it is done once per solver evaluation point:
//
//   Ceres calls PrepareForEvaluation(..., new_evaluation_point = true) after writing the
//   candidate parameters into the user's blocks and before any CostFunction::Evaluate. The
//   callback copies the control-pose blocks into an SE3Spline<double>, whose SetControlPoses
//   recomputes every knot delta and its Jacobians, and keeps a copy of the raw block values.
//
// A cost function holding a pointer to this callback asks Matches(first_index, parameters): if
// the four pose blocks it was handed hold exactly (bit for bit) the values the spline was built
// from, it reads the knots from the spline; otherwise it computes them from its own parameters
// (spline/segment.h, SegmentKnotData). So the cost functions keep Ceres' contract whatever
// calls them (ceres::GradientChecker, Problem::Evaluate, numeric differentiation): the shared
// path is an exact shortcut, never a different answer. (Ceres passes its own state pointers to
// Evaluate, not the user's blocks, hence a comparison of values, not of pointers.)
//
// Thread safety: PrepareForEvaluation and Update run while no cost function evaluates (Ceres
// calls the callback from the thread that drives the solver); Matches and spline() are const
// and may run concurrently afterwards.
#ifndef SPLINECAL_ESTIMATION_SPLINE_EVALUATION_CALLBACK_H_
#define SPLINECAL_ESTIMATION_SPLINE_EVALUATION_CALLBACK_H_

#include <ceres/evaluation_callback.h>

#include <cstdint>
#include <cstring>
#include <optional>
#include <vector>

#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment.h"

namespace splinecal {

class SplineEvaluationCallback : public ceres::EvaluationCallback {
 public:
  // blocks[i]: the control-pose block {px, py, pz, qx, qy, qz, qw} of T_i, as registered with
  // the ceres::Problem (owned by the caller, alive as long as this callback). Knot times
  // t_i = t0_ns + i dt_ns. Builds the spline from the blocks' current values. Throws
  // splinecal::Error for fewer than 4 blocks or dt_ns <= 0 (SE3Spline's preconditions).
  SplineEvaluationCallback(std::vector<double*> blocks, int64_t t0_ns, int64_t dt_ns)
      : blocks_(std::move(blocks)),
        values_(kPoseBlockSize * blocks_.size()),
        spline_(ReadBlocks(), t0_ns, dt_ns) {}

  void PrepareForEvaluation(bool evaluate_jacobians, bool new_evaluation_point) override {
    if (new_evaluation_point || num_updates_ == 0) Update();
  }

  // Rebuilds the spline from the blocks' current values (call after changing blocks outside a
  // solve).
  void Update() {
    spline_.SetControlPoses(ReadBlocks());
    ++num_updates_;
  }

  const SE3Splined& spline() const { return spline_; }
  int num_control_poses() const { return static_cast<int>(blocks_.size()); }

  // True when parameters[0..3] hold exactly the values of control poses first_index ..
  // first_index + 3 from which the spline was last built.
  bool Matches(int first_index, double const* const* parameters) const {
    if (first_index < 0 || first_index + kSplineOrder > num_control_poses()) return false;
    for (int k = 0; k < kSplineOrder; ++k) {
      const double* cached = &values_[kPoseBlockSize * (first_index + k)];
      if (std::memcmp(cached, parameters[k], sizeof(double) * kPoseBlockSize) != 0) return false;
    }
    return true;
  }

 private:
  std::vector<SE3d> ReadBlocks() {
    std::vector<SE3d> poses(blocks_.size());
    for (size_t i = 0; i < blocks_.size(); ++i) {
      std::memcpy(&values_[kPoseBlockSize * i], blocks_[i], sizeof(double) * kPoseBlockSize);
      poses[i] = PoseFromBlock(blocks_[i]);
    }
    return poses;
  }

  std::vector<double*> blocks_;
  std::vector<double> values_;  // raw block values the spline was built from, 7 per pose
  SE3Splined spline_;
  int64_t num_updates_ = 0;
};

namespace internal {

// The knot data of the segment whose four control-pose blocks are parameters[0..3] (control
// poses first_index .. first_index + 3): a view into the shared spline when `shared` is not
// null and Matches, else computed from the blocks into *local (with the Jacobian caches when
// with_jacobians). The view is valid while *shared (or *local) is unchanged.
inline SegmentKnots<double> SegmentKnotsFor(const SplineEvaluationCallback* shared,
                                            int first_index,
                                            double const* const* parameters,
                                            bool with_jacobians,
                                            std::optional<SegmentKnotData<double>>* local) {
  if (shared != nullptr && shared->Matches(first_index, parameters)) {
    Segment<double> segment;
    segment.index = first_index + 1;
    return shared->spline().Knots(segment);
  }
  local->emplace(PoseFromBlock(parameters[0]),
                 PoseFromBlock(parameters[1]),
                 PoseFromBlock(parameters[2]),
                 PoseFromBlock(parameters[3]),
                 with_jacobians,
                 first_index);
  return (*local)->knots();
}

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_SPLINE_EVALUATION_CALLBACK_H_
