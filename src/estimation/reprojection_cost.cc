#include "splinecal/estimation/reprojection_cost.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <utility>
#include <vector>

#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"

namespace splinecal {

namespace internal {

BodyState EvaluateBodyState(TrajectoryModel model,
                            const SegmentKnots<double>& knots,
                            const Segment<double>& segment) {
  BodyState state;
  EvaluateSegmentBody(
      model, knots, segment, &state.T_w_s, nullptr, &state.w_s, nullptr, &state.v_s, nullptr);
  return state;
}

bool ProjectPoint(const Camera& camera,
                  const SE3d& T_c_s,
                  const BodyState& state,
                  const Eigen::Vector3d& x_w,
                  double w,
                  bool with_jacobians,
                  PointProjection* projection) {
  const Eigen::Matrix3d R_t = state.T_w_s.rotationMatrix().transpose();  // R_w_s^T
  const Eigen::Vector3d& p_w_s = state.T_w_s.translation();
  const Eigen::Vector3d x_s = R_t * (x_w - w * p_w_s);
  const Eigen::Matrix3d R_c_s = T_c_s.rotationMatrix();
  const Eigen::Vector3d x_c = R_c_s * x_s + w * T_c_s.translation();
  Eigen::Matrix<double, 2, 3> J_pi;
  if (!camera.Project(x_c, &projection->uv, &J_pi)) return false;
  // d x_c / d e = R_c_s [-w I, [x_s]x] (header comment).
  const Eigen::Matrix<double, 2, 3> J_pi_R = J_pi * R_c_s;
  projection->J_uv_e.leftCols<3>() = -w * J_pi_R;
  projection->J_uv_e.rightCols<3>() = J_pi_R * Hat(x_s);
  // d uv / dt = J_uv_e [v_s; w_s].
  projection->uv_dot =
      projection->J_uv_e.leftCols<3>() * state.v_s + projection->J_uv_e.rightCols<3>() * state.w_s;
  if (with_jacobians) {
    projection->J_uv_xw = J_pi_R * R_t;
    projection->J_uv_w = J_pi * T_c_s.translation() - projection->J_uv_xw * p_w_s;
  }
  return true;
}

void RobustifyPoint(double k, Eigen::Vector2d* r, Eigen::Matrix2d* J_scale) {
  const double n = r->norm();
  if (!(k > 0.0) || n <= k) {
    if (J_scale != nullptr) J_scale->setIdentity();
    return;
  }
  const double root = std::sqrt(2.0 * k * n - k * k);  // sqrt(rho(n^2)) for Huber
  const double f = root / n;
  if (J_scale != nullptr) {
    // f'(n) = (k n / root - root) / n^2.
    const double f_prime = (k * n / root - root) / (n * n);
    *J_scale = f * Eigen::Matrix2d::Identity() + (f_prime / n) * (*r) * r->transpose();
  }
  *r *= f;
}

namespace {

// The knots of every segment a residual may touch, computed on demand from its pose blocks (or
// read from the shared spline) and kept for the rest of one Evaluate call.
class WindowKnots {
 public:
  // pose_indices: the residual's control poses (sorted, unique), parameters[0 ..] their blocks.
  WindowKnots(const ReprojectionOptions& settings,
              const std::vector<int>& pose_indices,
              double const* const* parameters,
              bool with_jacobians)
      : settings_(settings),
        pose_indices_(pose_indices),
        parameters_(parameters),
        with_jacobians_(with_jacobians) {
    // Knots are computed for the segments an evaluation visits (a landmark's reference and
    // observing segments, a few more in a rolling-shutter Newton solve), each kept in a deque,
    // whose elements never move (SegmentKnotData holds views into itself). The cache used to be
    // a vector over every control pose from the first index to the last, allocated and zeroed on
    // each Evaluate (2.5 kB per pose, and a landmark's two windows can lie seconds apart: about
    // 400 kB for an 8 s recording at 0.05 s knots). Under AddressSanitizer, whose allocator maps
    // and unmaps such blocks on every call, that made landmark calibrations about 30 to 60 times
    // slower than in Release (docs/reliability.md, "The sanitizer tests").
    entry_.assign(std::max(0, static_cast<int>(pose_indices_.size()) - 3), -1);
  }

  // The slot (parameter block index) of control pose `index`, or -1 when it is not held.
  int SlotOf(int index) const {
    const auto it = std::lower_bound(pose_indices_.begin(), pose_indices_.end(), index);
    if (it == pose_indices_.end() || *it != index) return -1;
    return static_cast<int>(it - pose_indices_.begin());
  }

  // The knots of segment i (control poses i-1 .. i+2), or nullptr when they are not all held.
  const SegmentKnots<double>* ForSegment(int i) {
    const int first = i - 1;
    const int slot = SlotOf(first);
    if (slot < 0 || slot + 3 >= static_cast<int>(pose_indices_.size()) ||
        pose_indices_[slot + 3] != first + 3) {
      return nullptr;
    }
    if (entry_[slot] < 0) {
      local_.emplace_back();
      views_.push_back(internal::SegmentKnotsFor(
          settings_.shared, first, parameters_ + slot, with_jacobians_, &local_.back()));
      entry_[slot] = static_cast<int>(views_.size()) - 1;
    }
    return &views_[entry_[slot]];
  }

 private:
  const ReprojectionOptions& settings_;
  const std::vector<int>& pose_indices_;
  double const* const* parameters_;
  bool with_jacobians_;
  std::vector<int> entry_;  // per slot that starts a segment: its index in views_, or -1
  std::deque<std::optional<SegmentKnotData<double>>> local_;
  std::deque<SegmentKnots<double>> views_;
};

// The state at an exposure time: what the last row evaluation of the Newton solve saw.
struct ExposureState {
  int segment_index = 0;
  Segment<double> segment;
  const SegmentKnots<double>* knots = nullptr;
  BodyState body;
};

// The last state StateAt computed within one Evaluate call. A global-shutter frame exposes all
// its corners at the same time, so its corners share one spline evaluation (and one control-pose
// Jacobian) instead of each recomputing the same numbers; rolling-shutter rows differ and miss.
struct StateMemo {
  bool valid = false;
  double t_s = 0.0;
  ExposureState state;
  bool has_pose_jacobian = false;
  ControlPoseJacobian<6> J_pose;  // of state.segment, once asked for
};

// Evaluates the body state at t_s (seconds since t0, IMU clock) from the window.
bool StateAt(const ReprojectionOptions& settings,
             WindowKnots* knots,
             double t_s,
             ExposureState* state,
             StateMemo* memo = nullptr) {
  if (memo != nullptr && memo->valid && memo->t_s == t_s) {
    *state = memo->state;
    return true;
  }
  int index = 0;
  double u = 0.0;
  SegmentPosition position;
  if (!settings.layout.SegmentAt(t_s, &position)) return false;
  index = position.index;
  u = position.u;
  const SegmentKnots<double>* k = knots->ForSegment(index);
  if (k == nullptr) return false;
  state->segment_index = index;
  state->segment = MakeSegment(index, u, settings.layout.dt_s());
  state->knots = k;
  state->body = EvaluateBodyState(settings.model, *k, state->segment);
  if (memo != nullptr) {
    memo->valid = true;
    memo->t_s = t_s;
    memo->state = *state;
    memo->has_pose_jacobian = false;
  }
  return true;
}

// The control-pose Jacobian of the pose at `state` (spline/trajectory_evaluation.h), from the
// memo when it holds that state's.
const ControlPoseJacobian<6>& PoseJacobianAt(TrajectoryModel model,
                                             const ExposureState& state,
                                             StateMemo* memo,
                                             ControlPoseJacobian<6>* storage) {
  const bool memo_state = memo->valid && memo->state.segment_index == state.segment_index &&
                          memo->state.segment.u == state.segment.u;
  if (memo_state && memo->has_pose_jacobian) return memo->J_pose;
  ControlPoseJacobian<6>* J = memo_state ? &memo->J_pose : storage;
  EvaluatePoseJacobian(model, *state.knots, state.segment, nullptr, J);
  if (memo_state) memo->has_pose_jacobian = true;
  return *J;
}

// Solves the exposure time of X_w = (x_w, w) in a frame at t_frame_s + shift (IMU clock) and
// projects it there. On success `state` and `projection` belong to the solution.
bool SolveAndProject(const ReprojectionOptions& settings,
                     WindowKnots* knots,
                     const SE3d& T_c_s,
                     double t_exposure_base_s,
                     double line_delay_s,
                     double tau0_s,
                     const Eigen::Vector3d& x_w,
                     double w,
                     ExposureSolution* solution,
                     ExposureState* state,
                     PointProjection* projection,
                     StateMemo* memo = nullptr) {
  const Camera& camera = *settings.camera;
  auto row_at = [&](double tau, double* v, double* v_dot) -> bool {
    if (!StateAt(settings, knots, t_exposure_base_s + tau, state, memo)) return false;
    if (!ProjectPoint(camera, T_c_s, state->body, x_w, w, false, projection)) return false;
    *v = projection->uv.y();
    *v_dot = projection->uv_dot.y();
    return true;
  };
  return SolveExposureTime(
      row_at, line_delay_s, camera.height, tau0_s, solution, settings.exposure);
}

// Zeroes every requested Jacobian block of a cost function.
void ZeroJacobians(const ceres::CostFunction& cost, double** jacobians) {
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  for (size_t i = 0; i < sizes.size(); ++i) {
    if (jacobians[i] != nullptr) {
      std::fill(jacobians[i], jacobians[i] + cost.num_residuals() * sizes[i], 0.0);
    }
  }
}

// Writes a 2-row tangent Jacobian of a pose block at rows row, row + 1.
void WritePoseRows(const Eigen::Matrix<double, 2, 6>& J_tangent,
                   const double* block,
                   double* jacobian,
                   int row) {
  if (jacobian == nullptr) return;
  LiftPoseJacobian(J_tangent, MakePoseBlockLift(block), jacobian + 7 * row);
}

// Adds a 2-row tangent Jacobian of a pose block at rows row, row + 1 (blocks a point touches
// twice: a landmark's reference and observing segments may share control poses).
void AddPoseRows(const Eigen::Matrix<double, 2, 6>& J_tangent,
                 const double* block,
                 double* jacobian,
                 int row) {
  if (jacobian == nullptr) return;
  double lifted[14];
  LiftPoseJacobian(J_tangent, MakePoseBlockLift(block), lifted);
  for (int i = 0; i < 14; ++i) jacobian[7 * row + i] += lifted[i];
}

std::vector<int> WindowIndices(const ControlPoseWindow& window) {
  std::vector<int> indices(window.num_poses);
  for (int i = 0; i < window.num_poses; ++i) indices[i] = window.first_index + i;
  return indices;
}

}  // namespace
}  // namespace internal

TargetFrameCostFunction::TargetFrameCostFunction(const ReprojectionOptions& settings,
                                                 const ControlPoseWindow& window,
                                                 double t_frame_s,
                                                 std::vector<TargetCornerObservation> corners)
    : settings_(settings), window_(window), t_frame_s_(t_frame_s), corners_(std::move(corners)) {
  CHECK(settings_.camera != nullptr);
  CHECK_GE(window_.num_poses, kSplineOrder);
  CHECK(!corners_.empty());
  set_num_residuals(2 * static_cast<int>(corners_.size()));
  for (int i = 0; i < window_.num_poses; ++i) mutable_parameter_block_sizes()->push_back(7);
  mutable_parameter_block_sizes()->push_back(7);  // T_cam_imu
  mutable_parameter_block_sizes()->push_back(1);  // time offset
  mutable_parameter_block_sizes()->push_back(1);  // line delay
  mutable_parameter_block_sizes()->push_back(7);  // T_w_t
  if (settings_.estimate_intrinsics) mutable_parameter_block_sizes()->push_back(kNumIntrinsics);
}

bool TargetFrameCostFunction::Evaluate(double const* const* parameters,
                                       double* residuals,
                                       double** jacobians) const {
  const int n = window_.num_poses;
  const SE3d T_c_s = settings_.T_cam_cref * PoseFromBlock(parameters[n]);
  const double shift = parameters[n + 1][0];
  const double line_delay = parameters[n + 2][0];
  const SE3d T_w_t = PoseFromBlock(parameters[n + 3]);
  if (!(line_delay >= 0.0) || !std::isfinite(shift)) return false;
  // With estimated intrinsics the camera of this evaluation is the block's.
  ReprojectionOptions settings = settings_;
  Camera estimated;
  if (settings_.estimate_intrinsics) {
    estimated = *settings_.camera;
    estimated.set_intrinsics(Eigen::Map<const IntrinsicsVector>(parameters[n + 4]));
    settings.camera = &estimated;
  }
  const Camera& camera = *settings.camera;
  const std::vector<int> indices = internal::WindowIndices(window_);
  internal::WindowKnots knots(settings_, indices, parameters, jacobians != nullptr);
  if (jacobians != nullptr) internal::ZeroJacobians(*this, jacobians);
  const double inv_sigma = 1.0 / settings_.sigma_px;
  const double k = settings_.huber_px * inv_sigma;
  const Eigen::Matrix3d R_w_t = T_w_t.rotationMatrix();
  const int height = camera.height;
  internal::StateMemo memo;
  for (size_t c = 0; c < corners_.size(); ++c) {
    const TargetCornerObservation& corner = corners_[c];
    const int row = 2 * static_cast<int>(c);
    const Eigen::Vector3d x_w = T_w_t * corner.p_t;
    ExposureSolution solution;
    internal::ExposureState state;
    internal::PointProjection projection;
    const double tau0 = line_delay * corner.uv.y();
    if (!internal::SolveAndProject(settings,
                                   &knots,
                                   T_c_s,
                                   t_frame_s_ + shift,
                                   line_delay,
                                   tau0,
                                   x_w,
                                   1.0,
                                   &solution,
                                   &state,
                                   &projection,
                                   &memo)) {
      return false;
    }
    Eigen::Vector2d r = (projection.uv - corner.uv) * inv_sigma;
    if (jacobians == nullptr) {
      internal::RobustifyPoint(k, &r, nullptr);
      residuals[row] = r.x();
      residuals[row + 1] = r.y();
      continue;
    }
    Eigen::Matrix2d S;
    internal::RobustifyPoint(k, &r, &S);
    residuals[row] = r.x();
    residuals[row + 1] = r.y();
    internal::ProjectPoint(camera, T_c_s, state.body, x_w, 1.0, true, &projection);
    const Eigen::Matrix2d M = RollingShutterCorrection(solution, line_delay, projection.uv_dot);
    const Eigen::Matrix2d F = inv_sigma * S * M;  // applied to every partial at fixed tau
    if (settings_.estimate_intrinsics && jacobians[n + 4] != nullptr) {
      const Eigen::Vector3d x_c =
          T_c_s * (state.body.T_w_s.inverse() * x_w);  // the point at the exposure
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, kNumIntrinsics> J_uv_intrinsics;
      camera.Project(x_c, &uv, nullptr, &J_uv_intrinsics);
      Eigen::Map<Eigen::Matrix<double, 2, kNumIntrinsics, Eigen::RowMajor>>(
          jacobians[n + 4] + row * kNumIntrinsics) = F * J_uv_intrinsics;
    }
    // Control poses of the exposure segment.
    ControlPoseJacobian<6> J_pose_storage;
    const ControlPoseJacobian<6>& J_pose =
        internal::PoseJacobianAt(settings_.model, state, &memo, &J_pose_storage);
    const Eigen::Matrix<double, 2, 6> F_J_e = F * projection.J_uv_e;
    for (int b = 0; b < kSplineOrder; ++b) {
      const int slot = J_pose.first_index + b - window_.first_index;
      internal::WritePoseRows(F_J_e * J_pose.blocks[b], parameters[slot], jacobians[slot], row);
    }
    // T_cam_imu: d x_c / d d = -(d x_c / d e).
    internal::WritePoseRows(-F_J_e, parameters[n], jacobians[n], row);
    if (jacobians[n + 1] != nullptr) {
      Eigen::Map<Eigen::Vector2d>(jacobians[n + 1] + row) = F * projection.uv_dot;
    }
    if (jacobians[n + 2] != nullptr) {
      Eigen::Map<Eigen::Vector2d>(jacobians[n + 2] + row) =
          inv_sigma * S * RollingShutterLineDelayJacobian(solution, height, projection.uv_dot);
    }
    if (jacobians[n + 3] != nullptr) {
      Eigen::Matrix<double, 3, 6> J_xw_d;
      J_xw_d.leftCols<3>() = R_w_t;
      J_xw_d.rightCols<3>() = -R_w_t * Hat(corner.p_t);
      const Eigen::Matrix<double, 2, 6> J = F * projection.J_uv_xw * J_xw_d;
      internal::WritePoseRows(J, parameters[n + 3], jacobians[n + 3], row);
    }
  }
  return true;
}

bool TargetFrameCostFunction::LinearizeGlobalShutter(double const* const* parameters,
                                                     bool with_target_pose,
                                                     bool with_intrinsics,
                                                     GlobalShutterLinearization* out) const {
  const int n = window_.num_poses;
  const double line_delay = parameters[n + 2][0];
  if (line_delay != 0.0 || (with_intrinsics && !settings_.estimate_intrinsics)) return false;
  const SE3d T_c_s = settings_.T_cam_cref * PoseFromBlock(parameters[n]);
  const double shift = parameters[n + 1][0];
  const SE3d T_w_t = PoseFromBlock(parameters[n + 3]);
  if (!std::isfinite(shift)) return false;
  Camera estimated;
  if (settings_.estimate_intrinsics) {
    estimated = *settings_.camera;
    estimated.set_intrinsics(Eigen::Map<const IntrinsicsVector>(parameters[n + 4]));
  }
  const Camera& camera = settings_.estimate_intrinsics ? estimated : *settings_.camera;
  const std::vector<int> indices = internal::WindowIndices(window_);
  internal::WindowKnots knots(settings_, indices, parameters, /*with_jacobians=*/true);
  internal::ExposureState state;
  if (!internal::StateAt(settings_, &knots, t_frame_s_ + shift, &state)) return false;
  EvaluatePoseJacobian(settings_.model, *state.knots, state.segment, nullptr, &out->J_pose);
  out->xi << state.body.v_s, state.body.w_s;
  const int m = num_residuals();
  const int target_columns = with_target_pose ? 6 : 0;
  out->r.resize(m);
  out->G.resize(m, 6 + target_columns + (with_intrinsics ? kNumIntrinsics : 0));
  const double inv_sigma = 1.0 / settings_.sigma_px;
  const double k = settings_.huber_px * inv_sigma;
  const Eigen::Matrix3d R_w_t = T_w_t.rotationMatrix();
  for (size_t c = 0; c < corners_.size(); ++c) {
    const TargetCornerObservation& corner = corners_[c];
    const int row = 2 * static_cast<int>(c);
    const Eigen::Vector3d x_w = T_w_t * corner.p_t;
    internal::PointProjection projection;
    if (!internal::ProjectPoint(camera, T_c_s, state.body, x_w, 1.0, true, &projection)) {
      return false;
    }
    Eigen::Vector2d r = (projection.uv - corner.uv) * inv_sigma;
    Eigen::Matrix2d S;
    internal::RobustifyPoint(k, &r, &S);
    out->r.segment<2>(row) = r;
    const Eigen::Matrix2d F = inv_sigma * S;  // M = I at line_delay 0
    out->G.block<2, 6>(row, 0) = F * projection.J_uv_e;
    if (with_target_pose) {
      Eigen::Matrix<double, 3, 6> J_xw_d;
      J_xw_d.leftCols<3>() = R_w_t;
      J_xw_d.rightCols<3>() = -R_w_t * Hat(corner.p_t);
      out->G.block<2, 6>(row, 6) = F * projection.J_uv_xw * J_xw_d;
    }
    if (with_intrinsics) {
      const Eigen::Vector3d x_c = T_c_s * (state.body.T_w_s.inverse() * x_w);
      Eigen::Vector2d uv;
      Eigen::Matrix<double, 2, kNumIntrinsics> J_uv_intrinsics;
      camera.Project(x_c, &uv, nullptr, &J_uv_intrinsics);
      out->G.block<2, kNumIntrinsics>(row, 6 + target_columns) = F * J_uv_intrinsics;
    }
  }
  return true;
}

LandmarkCostFunction::LandmarkCostFunction(const ReprojectionOptions& settings,
                                           std::vector<int> pose_indices,
                                           const LandmarkObservation& observation)
    : settings_(settings), pose_indices_(std::move(pose_indices)), observation_(observation) {
  CHECK(settings_.camera != nullptr);
  CHECK(!settings_.estimate_intrinsics) << "landmark residuals take the intrinsics as given";
  CHECK_GE(pose_indices_.size(), static_cast<size_t>(kSplineOrder));
  CHECK(std::is_sorted(pose_indices_.begin(), pose_indices_.end()));
  set_num_residuals(2);
  for (size_t i = 0; i < pose_indices_.size(); ++i) mutable_parameter_block_sizes()->push_back(7);
  mutable_parameter_block_sizes()->push_back(7);  // T_cam_imu
  mutable_parameter_block_sizes()->push_back(1);  // time offset
  mutable_parameter_block_sizes()->push_back(1);  // line delay
  mutable_parameter_block_sizes()->push_back(1);  // rho
}

std::vector<int> LandmarkCostFunction::UnionOfWindows(const ControlPoseWindow& a,
                                                      const ControlPoseWindow& b) {
  std::vector<int> indices;
  for (int i = 0; i < a.num_poses; ++i) indices.push_back(a.first_index + i);
  for (int i = 0; i < b.num_poses; ++i) indices.push_back(b.first_index + i);
  std::sort(indices.begin(), indices.end());
  indices.erase(std::unique(indices.begin(), indices.end()), indices.end());
  return indices;
}

bool LandmarkCostFunction::Evaluate(double const* const* parameters,
                                    double* residuals,
                                    double** jacobians) const {
  const int n = static_cast<int>(pose_indices_.size());
  const SE3d T_c_s = settings_.T_cam_cref * PoseFromBlock(parameters[n]);
  const double shift = parameters[n + 1][0];
  const double line_delay = parameters[n + 2][0];
  const double rho = parameters[n + 3][0];
  if (!(line_delay >= 0.0) || !std::isfinite(shift) || !std::isfinite(rho)) return false;
  internal::WindowKnots knots(settings_, pose_indices_, parameters, jacobians != nullptr);
  // Reference: explicit exposure time (its row is observed).
  const double t_r =
      observation_.t_reference_frame_s + shift + line_delay * observation_.reference_row;
  internal::ExposureState reference;
  if (!internal::StateAt(settings_, &knots, t_r, &reference)) return false;
  const SE3d T_s_c = T_c_s.inverse();
  const Eigen::Vector3d x_sr = T_s_c.so3() * observation_.ray + rho * T_s_c.translation();
  const Eigen::Matrix3d R_w_sr = reference.body.T_w_s.rotationMatrix();
  const Eigen::Vector3d& p_w_sr = reference.body.T_w_s.translation();
  const Eigen::Vector3d x_w = R_w_sr * x_sr + rho * p_w_sr;
  // Observation.
  ExposureSolution solution;
  internal::ExposureState state;
  internal::PointProjection projection;
  if (!internal::SolveAndProject(settings_,
                                 &knots,
                                 T_c_s,
                                 observation_.t_frame_s + shift,
                                 line_delay,
                                 line_delay * observation_.uv.y(),
                                 x_w,
                                 rho,
                                 &solution,
                                 &state,
                                 &projection)) {
    return false;
  }
  const double inv_sigma = 1.0 / settings_.sigma_px;
  Eigen::Vector2d r = (projection.uv - observation_.uv) * inv_sigma;
  const double k = settings_.huber_px * inv_sigma;
  if (jacobians == nullptr) {
    internal::RobustifyPoint(k, &r, nullptr);
    residuals[0] = r.x();
    residuals[1] = r.y();
    return true;
  }
  Eigen::Matrix2d S;
  internal::RobustifyPoint(k, &r, &S);
  residuals[0] = r.x();
  residuals[1] = r.y();
  internal::ZeroJacobians(*this, jacobians);
  internal::ProjectPoint(*settings_.camera, T_c_s, state.body, x_w, rho, true, &projection);
  const Eigen::Matrix2d M = RollingShutterCorrection(solution, line_delay, projection.uv_dot);
  const Eigen::Matrix2d F = inv_sigma * S * M;
  // A_r = d x_w / d e_r = R_w_sr [rho I, -[x_sr]x].
  Eigen::Matrix<double, 3, 6> A_r;
  A_r.leftCols<3>() = rho * R_w_sr;
  A_r.rightCols<3>() = -R_w_sr * Hat(x_sr);
  const Eigen::Matrix<double, 2, 3> F_J_xw = F * projection.J_uv_xw;
  // Observing segment.
  ControlPoseJacobian<6> J_pose;
  EvaluatePoseJacobian(settings_.model, *state.knots, state.segment, nullptr, &J_pose);
  const Eigen::Matrix<double, 2, 6> F_J_e = F * projection.J_uv_e;
  for (int b = 0; b < kSplineOrder; ++b) {
    const int slot = knots.SlotOf(J_pose.first_index + b);
    internal::AddPoseRows(F_J_e * J_pose.blocks[b], parameters[slot], jacobians[slot], 0);
  }
  // Reference segment.
  ControlPoseJacobian<6> J_reference;
  EvaluatePoseJacobian(settings_.model, *reference.knots, reference.segment, nullptr, &J_reference);
  const Eigen::Matrix<double, 2, 6> F_J_er = F_J_xw * A_r;
  for (int b = 0; b < kSplineOrder; ++b) {
    const int slot = knots.SlotOf(J_reference.first_index + b);
    internal::AddPoseRows(F_J_er * J_reference.blocks[b], parameters[slot], jacobians[slot], 0);
  }
  // T_cam_imu: observing side -(d x_c / d e); reference side R_w_sr [-rho I, [x_sr]x] = -A_r.
  internal::WritePoseRows(-F_J_e - F_J_er, parameters[n], jacobians[n], 0);
  // Reference time: d x_w / d t_r = A_r xi_r.
  Vector6d xi_r;
  xi_r << reference.body.v_s, reference.body.w_s;
  const Eigen::Vector2d G_tr = projection.J_uv_xw * (A_r * xi_r);  // d G / d t_r (unscaled)
  if (jacobians[n + 1] != nullptr) {
    Eigen::Map<Eigen::Vector2d> J(jacobians[n + 1]);
    J = F * (projection.uv_dot + G_tr);
  }
  if (jacobians[n + 2] != nullptr) {
    Eigen::Map<Eigen::Vector2d> J(jacobians[n + 2]);
    J = F * G_tr * observation_.reference_row +
        inv_sigma * S *
            RollingShutterLineDelayJacobian(solution, settings_.camera->height, projection.uv_dot);
  }
  if (jacobians[n + 3] != nullptr) {
    const Eigen::Vector3d dxw_drho = R_w_sr * T_s_c.translation() + p_w_sr;
    Eigen::Map<Eigen::Vector2d> J(jacobians[n + 3]);
    J = F_J_xw * dxw_drho + F * projection.J_uv_w;
  }
  return true;
}

}  // namespace splinecal
