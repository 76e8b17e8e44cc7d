// SE3Spline<T>: the trajectory T_w_s(t) of uniform control poses in SE(3), by default the
// cumulative cubic B-spline on SE(3) ([CONVENTIONS "The spline"], [seed000 §3], [Lovegrove13]).
//
//   Control poses T_i, i = 0..n-1 (n >= 4), at knot times t_i = t0 + i dt (dt > 0). For t in
//   [t_i, t_{i+1}), u = (t - t_i) / dt:
//       T(t) = T_{i-1} prod_{j=1..3} Exp(Bt_j(u) Omega_{i+j-1}),   Omega_k = Log(T_{k-1}^-1 T_k),
//   Bt from spline/basis.h. Valid times are [t_1, t_{n-2}]; the end t_{n-2} evaluates the last
//   segment (i = n-3) at u = 1. Any other time throws splinecal::Error.
//
// Model. A spline constructed with TrajectoryModel::kSplitSO3R3 interpolates the same control
// poses as the split SO(3) x R^3 spline instead (spline/trajectory_model.h,
// spline/split_segment.h): the same orientation, the positions blended as an ordinary cubic
// B-spline. Every evaluation and Jacobian below follows model(); the knot caches serve both.
//
// Time. Files carry int64 nanoseconds near 1.4e18, which a double cannot hold to the
// nanosecond. The spline keeps t0 as int64 ns and dt as int64 ns; evaluation takes either an
// absolute int64 time (SegmentAtNs, exact segment lookup in integer arithmetic) or a time in
// seconds RELATIVE to t0 of scalar type T (SegmentAt: a ceres::Jet time offset passes through u).
// Use TimeSinceT0(t_ns) to convert.
//
// Caches. Omega_k, its scaled-exponential invariants and (double only) its Jacobians
// Jr^-1(Omega_k), Jl^-1(Omega_k) are computed when control poses change (constructor,
// SetControlPose), so an evaluation costs three scaled exponentials (one sin/cos each) plus the
// products of spline/segment.h. One lookup (SegmentAt) feeds every evaluation:
//
//     const Segment<double> seg = spline.SegmentAtNs(t_ns);
//     SE3d T_w_s; Eigen::Vector3d w_s, a_w;
//     spline.Evaluate(seg, &T_w_s, &w_s, nullptr, nullptr, &a_w);
//     ControlPoseJacobian<3> J_ws_ctrl;                        // double only
//     spline.EvaluateAngularVelocityJacobian(seg, &w_s, &J_ws_ctrl);
//
// Derivatives (spline/segment.h) and Jacobians (spline/segment_jacobians.h) are analytic; the
// Jacobians use the RIGHT perturbation T_k Exp(d), d = [rho; phi] (lie/se3.h).
//
// Use in Ceres (fitting the control poses). Each control pose is a 7-parameter block
// {px, py, pz, qx, qy, qz, qw} with lie/se3_manifold.h's SE3Manifold (the same RIGHT
// perturbation as the Jacobians here). Two ways to write an analytic IMU cost function:
//   * cached (fast): a ceres::EvaluationCallback calls SetControlPoses (or SetControlPose)
//     from the blocks in PrepareForEvaluation, so the knot caches are refreshed once per
//     evaluation point; each cost function keeps its Segment (fixed measurement time) and calls
//     PredictGyroWithJacobian / PredictAccelWithJacobian (imu/imu_model.h) on spline.Knots(seg).
//   * self-contained: build SegmentKnotData<double> from the four blocks inside Evaluate
//     (three Logs and Jacobian caches per call; ~4x slower, see bench/spline_bench.cc).
// Either way, Ceres wants d residual / d block (3x7): J_ambient = J_tangent * MinusJacobian(x)
// (then J_ambient * PlusJacobian(x) = J_tangent); bench/spline_bench.cc, LiftToPoseBlock, shows
// it. Automatic differentiation works on the same templates (SegmentKnotData<Jet>, PredictImu).
//
// Thread safety: const methods may run concurrently; SetControlPose must not run concurrently
// with anything else on the same spline.
#ifndef SPLINECAL_SPLINE_SE3_SPLINE_H_
#define SPLINECAL_SPLINE_SE3_SPLINE_H_

#include <ceres/jet.h>

#include <Eigen/Core>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/types.h"
#include "splinecal/spline/basis.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

namespace internal {

// The value part of a scalar (double, or the .a of a ceres::Jet).
inline double ScalarPart(double x) { return x; }
template <typename U, int N>
double ScalarPart(const ceres::Jet<U, N>& x) {
  return ScalarPart(x.a);
}

}  // namespace internal

template <typename T>
class SE3Spline {
 public:
  using Scalar = T;

  // control_poses[i] = T_w_s at t_i = t0_ns + i * dt_ns, interpolated by `model`. Throws
  // splinecal::Error if there are fewer than 4 control poses, dt_ns <= 0, or the last knot time
  // overflows int64.
  SE3Spline(std::vector<SE3<T>> control_poses,
            int64_t t0_ns,
            int64_t dt_ns,
            TrajectoryModel model = TrajectoryModel::kSE3)
      : control_poses_(std::move(control_poses)), model_(model) {
    if (control_poses_.size() < static_cast<size_t>(kSplineOrder)) {
      throw Error("SE3Spline: needs at least 4 control poses, got " +
                  std::to_string(control_poses_.size()));
    }
    if (control_poses_.size() > static_cast<size_t>(std::numeric_limits<int>::max() / 2)) {
      throw Error("SE3Spline: too many control poses (" + std::to_string(control_poses_.size()) +
                  ")");
    }
    if (dt_ns <= 0) {
      throw Error("SE3Spline: knot spacing dt must be > 0, got " + std::to_string(dt_ns) + " ns");
    }
    int64_t span_ns = 0;
    int64_t last_ns = 0;
    if (__builtin_mul_overflow(static_cast<int64_t>(control_poses_.size() - 1), dt_ns, &span_ns) ||
        __builtin_add_overflow(t0_ns, span_ns, &last_ns)) {
      throw Error("SE3Spline: knot times overflow int64 nanoseconds (t0 = " +
                  std::to_string(t0_ns) + " ns, dt = " + std::to_string(dt_ns) + " ns, " +
                  std::to_string(control_poses_.size()) + " control poses)");
    }
    layout_.t0_ns = t0_ns;
    layout_.dt_ns = dt_ns;
    layout_.num_control_poses = static_cast<int>(control_poses_.size());
    const int n = num_control_poses();
    rotations_.resize(n);
    for (int i = 0; i < n; ++i) rotations_[i] = control_poses_[i].so3().matrix();
    deltas_.resize(n - 1);
    if constexpr (std::is_same_v<T, double>) delta_jacobians_.resize(n - 1);
    for (int k = 1; k < n; ++k) UpdateDelta(k);
  }

  // The interpolation of the control poses (spline/trajectory_model.h).
  TrajectoryModel model() const { return model_; }

  // Knot times and the segment lookup (spline/knot_layout.h).
  const KnotLayout& layout() const { return layout_; }
  int num_control_poses() const { return layout_.num_control_poses; }
  int num_segments() const { return num_control_poses() - 3; }
  int64_t t0_ns() const { return layout_.t0_ns; }
  int64_t dt_ns() const { return layout_.dt_ns; }
  // Knot spacing [s].
  double dt() const { return layout_.dt_s(); }
  // t_i = t0 + i dt [ns].
  int64_t knot_time_ns(int i) const { return layout_.knot_time_ns(i); }
  // Valid time range [t_1, t_{n-2}] in absolute ns and in seconds relative to t0.
  int64_t start_time_ns() const { return layout_.start_time_ns(); }
  int64_t end_time_ns() const { return layout_.end_time_ns(); }
  double start_time() const { return layout_.start_time(); }
  double end_time() const { return layout_.end_time(); }
  // Seconds since t0, exact integer subtraction first (no loss near 1.4e18 ns).
  double TimeSinceT0(int64_t t_ns) const { return layout_.TimeSinceT0(t_ns); }

  const std::vector<SE3<T>>& control_poses() const { return control_poses_; }
  const SE3<T>& control_pose(int i) const {
    CheckIndex(i);
    return control_poses_[i];
  }

  // Replaces T_i and refreshes the caches of Omega_i and Omega_{i+1}.
  void SetControlPose(int i, const SE3<T>& T_w_i) {
    CheckIndex(i);
    control_poses_[i] = T_w_i;
    rotations_[i] = T_w_i.so3().matrix();
    if (i >= 1) UpdateDelta(i);
    if (i + 1 < num_control_poses()) UpdateDelta(i + 1);
  }

  // Replaces every control pose (same count) and refreshes all caches.
  void SetControlPoses(const std::vector<SE3<T>>& control_poses) {
    if (control_poses.size() != control_poses_.size()) {
      throw Error("SE3Spline::SetControlPoses: expected " + std::to_string(control_poses_.size()) +
                  " control poses, got " + std::to_string(control_poses.size()));
    }
    control_poses_ = control_poses;
    for (int i = 0; i < num_control_poses(); ++i) rotations_[i] = control_poses_[i].so3().matrix();
    for (int k = 1; k < num_control_poses(); ++k) UpdateDelta(k);
  }

  // The segment of t_s, a time in SECONDS RELATIVE TO t0 (T may carry a Jet time offset).
  // Throws splinecal::Error outside [t_1, t_{n-2}] (or for NaN).
  Segment<T> SegmentAt(const T& t_s) const {
    SegmentPosition position;
    if (!layout_.SegmentAt(internal::ScalarPart(t_s), &position)) {
      std::ostringstream message;
      message.precision(17);
      message << "SE3Spline: time " << internal::ScalarPart(t_s)
              << " s (relative to t0) is outside the valid range [t_1, t_{n-2}] = [" << start_time()
              << ", " << end_time() << "] s";
      throw Error(message.str());
    }
    const int index = position.index;
    // u = t/dt - i keeps the Jet part of t_s; snapped ends clamp the value only.
    T u = t_s / dt() - T(static_cast<double>(index));
    const double u_value = internal::ScalarPart(u);
    if (u_value < 0.0) u += T(-u_value);
    if (u_value > 1.0) u -= T(u_value - 1.0);
    return MakeSegment(index, u, dt());
  }

  // The segment of an absolute time t_ns [ns] (exact integer lookup). Throws splinecal::Error
  // outside [t_1, t_{n-2}].
  Segment<T> SegmentAtNs(int64_t t_ns) const {
    SegmentPosition position;
    if (!layout_.SegmentAtNs(t_ns, &position)) {
      throw Error("SE3Spline: time " + std::to_string(t_ns) +
                  " ns is outside the valid range [t_1, t_{n-2}] = [" +
                  std::to_string(start_time_ns()) + ", " + std::to_string(end_time_ns()) + "] ns");
    }
    return MakeSegment(position.index, T(position.u), dt());
  }

  // The knot data of `segment` (a view into this spline's caches).
  SegmentKnots<T> Knots(const Segment<T>& segment) const {
    const int first = segment.first_index();
    CHECK(first >= 0 && first + 3 < num_control_poses()) << "segment index out of range";
    SegmentKnots<T> knots;
    knots.first_index = first;
    knots.T_first = &control_poses_[first];
    knots.R_first = &rotations_[first];
    knots.deltas = &deltas_[first];
    if constexpr (std::is_same_v<T, double>) knots.jacobians = &delta_jacobians_[first];
    return knots;
  }

  // One-pass evaluation of model(); every output optional (spline/trajectory_evaluation.h,
  // EvaluateSegment): pose T_w_s, body angular velocity w_s [rad/s], body angular acceleration
  // w_dot_s [rad/s^2], world linear velocity v_w [m/s] and acceleration a_w [m/s^2].
  void Evaluate(const Segment<T>& segment,
                SE3<T>* T_w_s,
                Vector3<T>* w_s = nullptr,
                Vector3<T>* w_dot_s = nullptr,
                Vector3<T>* v_w = nullptr,
                Vector3<T>* a_w = nullptr) const {
    EvaluateSegment(model_, Knots(segment), segment, T_w_s, w_s, w_dot_s, v_w, a_w);
  }

  // Named evaluations: one quantity of the segment (the same one-pass Evaluate).
  SE3<T> Pose(const Segment<T>& segment) const {
    SE3<T> T_w_s;
    Evaluate(segment, &T_w_s);
    return T_w_s;
  }
  // Body angular velocity w_s [rad/s] and acceleration w_dot_s [rad/s^2].
  Vector3<T> AngularVelocity(const Segment<T>& segment) const {
    Vector3<T> w_s;
    Evaluate(segment, nullptr, &w_s);
    return w_s;
  }
  Vector3<T> AngularAcceleration(const Segment<T>& segment) const {
    Vector3<T> w_dot_s;
    Evaluate(segment, nullptr, nullptr, &w_dot_s);
    return w_dot_s;
  }
  // World linear velocity v_w [m/s] and acceleration a_w [m/s^2].
  Vector3<T> LinearVelocity(const Segment<T>& segment) const {
    Vector3<T> v_w;
    Evaluate(segment, nullptr, nullptr, nullptr, &v_w);
    return v_w;
  }
  Vector3<T> LinearAcceleration(const Segment<T>& segment) const {
    Vector3<T> a_w;
    Evaluate(segment, nullptr, nullptr, nullptr, nullptr, &a_w);
    return a_w;
  }

  // Conveniences: the pose at a relative time [s] or an absolute time [ns].
  SE3<T> Pose(const T& t_s) const {
    SE3<T> T_w_s;
    Evaluate(SegmentAt(t_s), &T_w_s);
    return T_w_s;
  }
  SE3<T> PoseNs(int64_t t_ns) const {
    SE3<T> T_w_s;
    Evaluate(SegmentAtNs(t_ns), &T_w_s);
    return T_w_s;
  }

  // Analytic Jacobians of model() with respect to the segment's control poses (T = double only;
  // spline/segment_jacobians.h, spline/split_segment_jacobians.h). Value outputs may be nullptr.
  void EvaluatePoseJacobian(const Segment<double>& segment,
                            SE3d* T_w_s,
                            ControlPoseJacobian<6>* J_pose_ctrl) const {
    static_assert(std::is_same_v<T, double>, "analytic Jacobians need SE3Spline<double>");
    splinecal::EvaluatePoseJacobian(model_, Knots(segment), segment, T_w_s, J_pose_ctrl);
  }
  void EvaluateAngularVelocityJacobian(const Segment<double>& segment,
                                       Eigen::Vector3d* w_s,
                                       ControlPoseJacobian<3>* J_ws_ctrl) const {
    static_assert(std::is_same_v<T, double>, "analytic Jacobians need SE3Spline<double>");
    splinecal::EvaluateAngularVelocityJacobian(Knots(segment), segment, w_s, J_ws_ctrl);
  }
  void EvaluateLinearAccelerationJacobian(const Segment<double>& segment,
                                          Eigen::Vector3d* a_w,
                                          ControlPoseJacobian<3>* J_aw_ctrl) const {
    static_assert(std::is_same_v<T, double>, "analytic Jacobians need SE3Spline<double>");
    splinecal::EvaluateLinearAccelerationJacobian(model_, Knots(segment), segment, a_w, J_aw_ctrl);
  }

 private:
  void CheckIndex(int i) const {
    if (i < 0 || i >= num_control_poses()) {
      throw Error("SE3Spline: control pose index " + std::to_string(i) + " out of range [0, " +
                  std::to_string(num_control_poses()) + ")");
    }
  }

  // Omega_k from T_{k-1}, T_k (stored at deltas_[k-1]).
  void UpdateDelta(int k) {
    deltas_[k - 1] = MakeKnotDelta(control_poses_[k - 1], control_poses_[k]);
    if constexpr (std::is_same_v<T, double>) {
      delta_jacobians_[k - 1] = MakeKnotDeltaJacobians(deltas_[k - 1]);
    }
  }

  std::vector<SE3<T>> control_poses_;
  TrajectoryModel model_;
  std::vector<Matrix3<T>> rotations_;  // control pose rotation matrices
  KnotLayout layout_;
  std::vector<KnotDelta<T>> deltas_;                 // deltas_[k-1] = Omega_k, k = 1..n-1
  std::vector<KnotDeltaJacobians> delta_jacobians_;  // double only
};

using SE3Splined = SE3Spline<double>;

}  // namespace splinecal

#endif  // SPLINECAL_SPLINE_SE3_SPLINE_H_
