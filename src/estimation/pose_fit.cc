#include "splinecal/estimation/pose_fit.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <utility>

#include "splinecal/error.h"
#include "splinecal/estimation/detail/pose_block_jacobian.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

using RowMajor6x7 = Eigen::Matrix<double, 6, 7, Eigen::RowMajor>;

// The pose residual of one spline segment: 6 rows per measured pose in the segment,
// [p(t) - p_m; w_R Log(R_m^T R(t))], over the segment's four control-pose blocks.
class SegmentPoseCost : public ceres::CostFunction {
 public:
  SegmentPoseCost(std::vector<double> u,
                  std::vector<SE3d> measured,
                  double dt_s,
                  double w_rot,
                  TrajectoryModel model)
      : u_(std::move(u)),
        measured_(std::move(measured)),
        dt_s_(dt_s),
        w_rot_(w_rot),
        model_(model) {
    set_num_residuals(6 * static_cast<int>(u_.size()));
    for (int k = 0; k < kSplineOrder; ++k) mutable_parameter_block_sizes()->push_back(7);
  }

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    std::array<SE3d, kSplineOrder> P;
    for (int k = 0; k < kSplineOrder; ++k) {
      const Eigen::Map<const Eigen::Matrix<double, 7, 1>> block(parameters[k]);
      if (!block.allFinite() || block.tail<4>().squaredNorm() < 1e-12) return false;
      P[k] = PoseFromBlock(parameters[k]);
    }
    bool want_jacobians = false;
    std::array<RowMajor6x7, kSplineOrder> minus;
    if (jacobians != nullptr) {
      for (int k = 0; k < kSplineOrder; ++k) {
        if (jacobians[k] == nullptr) continue;
        want_jacobians = true;
        manifold_.MinusJacobian(parameters[k], minus[k].data());
      }
    }
    const SegmentKnotData<double> data(P[0], P[1], P[2], P[3], want_jacobians);
    const int rows = num_residuals();
    for (size_t j = 0; j < u_.size(); ++j) {
      const Segment<double> segment = MakeSegment(1, u_[j], dt_s_);
      SE3d T_w_s;
      ControlPoseJacobian<6> J;
      EvaluatePoseJacobian(model_, data.knots(), segment, &T_w_s, want_jacobians ? &J : nullptr);
      const Eigen::Vector3d phi = (measured_[j].so3().inverse() * T_w_s.so3()).Log();
      Eigen::Map<Vector6d> r(residuals + 6 * j);
      r.head<3>() = T_w_s.translation() - measured_[j].translation();
      r.tail<3>() = w_rot_ * phi;
      if (!r.allFinite()) return false;
      if (!want_jacobians) continue;
      const Eigen::Matrix3d R_w_s = T_w_s.so3().matrix();
      const Eigen::Matrix3d J_r_phi = w_rot_ * RightJacobianInverseSO3(phi);
      for (int k = 0; k < kSplineOrder; ++k) {
        if (jacobians[k] == nullptr) continue;
        Matrix6d J_tangent;
        J_tangent.topRows<3>() = R_w_s * J.blocks[k].topRows<3>();
        J_tangent.bottomRows<3>() = J_r_phi * J.blocks[k].bottomRows<3>();
        Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, 7, Eigen::RowMajor>> J_ambient(
            jacobians[k], rows, 7);
        J_ambient.block<6, 7>(6 * static_cast<int>(j), 0) = J_tangent * minus[k];
      }
    }
    return true;
  }

 private:
  std::vector<double> u_;
  std::vector<SE3d> measured_;
  double dt_s_;
  double w_rot_;
  TrajectoryModel model_;
  SE3Manifold manifold_;
};

// w_s (Omega_i - Omega_{i+1}), Omega_k = Log(T_{k-1}^-1 T_k): the weak smoothness prior
// (pose_fit.h). Under the right perturbations T_k Exp(d_k) (spline/segment.h, KnotDeltaJacobians)
//   d Omega_k / d d_k = Jr^-1(Omega_k),   d Omega_k / d d_{k-1} = -Jl^-1(Omega_k),
// so d r / d d_{i-1} = -w Jl^-1(Omega_i), d r / d d_i = w (Jr^-1(Omega_i) + Jl^-1(Omega_{i+1})),
// d r / d d_{i+1} = -w Jr^-1(Omega_{i+1}), lifted to the ambient blocks
// (estimation/detail/pose_block_jacobian.h). Analytic: its automatic differentiation through three
// SE(3) logarithms was most of a pose fit's Jacobian time (docs/performance.md, 711d43c).
class SmoothnessPriorCost : public ceres::SizedCostFunction<6, 7, 7, 7> {
 public:
  explicit SmoothnessPriorCost(double weight) : weight_(weight) {}

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override {
    const SE3d T_a = PoseFromBlock(parameters[0]);
    const SE3d T_b = PoseFromBlock(parameters[1]);
    const SE3d T_c = PoseFromBlock(parameters[2]);
    const Vector6d omega_ab = (T_a.inverse() * T_b).Log();
    const Vector6d omega_bc = (T_b.inverse() * T_c).Log();
    Eigen::Map<Vector6d> r(residuals);
    r = weight_ * (omega_ab - omega_bc);
    if (!r.allFinite()) return false;
    if (jacobians == nullptr) return true;
    const Matrix6d J[3] = {
        -weight_ * LeftJacobianInverseSE3(omega_ab),
        weight_ * (RightJacobianInverseSE3(omega_ab) + LeftJacobianInverseSE3(omega_bc)),
        -weight_ * RightJacobianInverseSE3(omega_bc)};
    for (int k = 0; k < 3; ++k) {
      if (jacobians[k] == nullptr) continue;
      internal::LiftPoseJacobian(J[k], internal::MakePoseBlockLift(parameters[k]), jacobians[k]);
    }
    return true;
  }

 private:
  double weight_;
};

// The measured pose at t_ns (clamped to the ends): position linear, rotation geodesic.
SE3d InterpolatePose(const std::vector<StampedPose>& poses, int64_t t_ns) {
  if (t_ns <= poses.front().t_ns) {
    return SE3d(SO3d::FromQuaternion(poses.front().q), poses.front().p);
  }
  if (t_ns >= poses.back().t_ns) {
    return SE3d(SO3d::FromQuaternion(poses.back().q), poses.back().p);
  }
  const auto after = std::upper_bound(
      poses.begin(), poses.end(), t_ns, [](int64_t t, const StampedPose& p) { return t < p.t_ns; });
  const StampedPose& a = *(after - 1);
  const StampedPose& b = *after;
  const double s = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  const SO3d R_a = SO3d::FromQuaternion(a.q);
  const SO3d R_b = SO3d::FromQuaternion(b.q);
  return SE3d(R_a * SO3d::Exp(s * (R_a.inverse() * R_b).Log()), a.p + s * (b.p - a.p));
}

class ProgressCallback : public ceres::IterationCallback {
 public:
  explicit ProgressCallback(std::function<void(const std::string&)> progress)
      : progress_(std::move(progress)) {}

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    progress_(StringPrintf("pose fit: iteration %d, cost %.6e, |gradient| %.3e, |step| %.3e",
                           summary.iteration,
                           summary.cost,
                           summary.gradient_max_norm,
                           summary.step_norm));
    return ceres::SOLVER_CONTINUE;
  }

 private:
  std::function<void(const std::string&)> progress_;
};

// Ends the solve once kRejectedSteps consecutive steps below kRoundingStep were rejected: the
// cost then sits at its rounding floor, and Levenberg-Marquardt would only shrink its trust
// region, rejecting step after step at the same parameters, until the parameter tolerance ends
// the solve there (the resampling of calibrate's initial guess: 2 useful iterations, then 6
// rejected ones of 0.11 s each). Rejected steps leave the parameters as they are, so the result
// is the one the tolerance would have ended on.
class RoundingFloorStop : public ceres::IterationCallback {
 public:
  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
    const bool stuck = summary.iteration > 0 && !summary.step_is_successful &&
                       summary.step_norm < kRoundingStep;
    rejected_ = stuck ? rejected_ + 1 : 0;
    return rejected_ >= kRejectedSteps ? ceres::SOLVER_TERMINATE_SUCCESSFULLY
                                       : ceres::SOLVER_CONTINUE;
  }

 private:
  // A step of a micrometre (and microradian) over all control poses together.
  static constexpr double kRoundingStep = 1e-6;
  static constexpr int kRejectedSteps = 2;
  int rejected_ = 0;
};

}  // namespace

namespace internal {

ceres::CostFunction* NewSegmentPoseCost(std::vector<double> u,
                                        std::vector<SE3d> measured,
                                        double dt_s,
                                        double rotation_weight_m_per_rad,
                                        TrajectoryModel trajectory) {
  CHECK_EQ(u.size(), measured.size());
  CHECK(!u.empty());
  return new SegmentPoseCost(
      std::move(u), std::move(measured), dt_s, rotation_weight_m_per_rad, trajectory);
}

ceres::CostFunction* NewSmoothnessPriorCost(double weight) {
  return new SmoothnessPriorCost(weight);
}

}  // namespace internal

void PoseFitErrors(const SE3Splined& spline,
                   const std::vector<StampedPose>& poses,
                   PoseFitResult* result) {
  double sum_p = 0.0;
  double sum_r = 0.0;
  result->num_poses = 0;
  result->max_position_error_m = 0.0;
  result->max_rotation_error_deg = 0.0;
  for (const StampedPose& pose : poses) {
    if (pose.t_ns < spline.start_time_ns() || pose.t_ns > spline.end_time_ns()) continue;
    const SE3d T_w_s = spline.PoseNs(pose.t_ns);
    const double e_p = (T_w_s.translation() - pose.p).norm();
    const double e_r =
        (SO3d::FromQuaternion(pose.q).inverse() * T_w_s.so3()).Log().norm() * 180.0 / kPi;
    sum_p += e_p * e_p;
    sum_r += e_r * e_r;
    result->max_position_error_m = std::max(result->max_position_error_m, e_p);
    result->max_rotation_error_deg = std::max(result->max_rotation_error_deg, e_r);
    ++result->num_poses;
  }
  const double n = std::max<double>(1.0, static_cast<double>(result->num_poses));
  result->position_rms_m = std::sqrt(sum_p / n);
  result->rotation_rms_deg = std::sqrt(sum_r / n);
}

PoseFitResult FitControlPoses(const std::vector<StampedPose>& poses,
                              const KnotLayout& layout,
                              const PoseFitOptions& options) {
  if (layout.num_control_poses < kSplineOrder || layout.dt_ns <= 0) {
    throw Error("pose fit: the knot layout needs dt > 0 and at least 4 control poses");
  }
  for (size_t j = 1; j < poses.size(); ++j) {
    if (poses[j].t_ns <= poses[j - 1].t_ns) {
      throw Error("pose fit: pose timestamps must be strictly increasing (pose " +
                  std::to_string(j) + ")");
    }
  }
  if (poses.size() < 2) throw Error("pose fit: needs at least 2 poses");

  // Initial control poses and the segment of every pose (one lookup on the initial spline).
  std::vector<SE3d> initial(layout.num_control_poses);
  for (int i = 0; i < layout.num_control_poses; ++i) {
    initial[i] = InterpolatePose(poses, layout.t0_ns + static_cast<int64_t>(i) * layout.dt_ns);
  }
  const SE3Splined initial_spline(initial, layout.t0_ns, layout.dt_ns);
  const int num_segments = initial_spline.num_segments();
  std::vector<std::vector<double>> segment_u(num_segments);
  std::vector<std::vector<SE3d>> segment_poses(num_segments);
  int64_t used = 0;
  for (const StampedPose& pose : poses) {
    if (pose.t_ns < initial_spline.start_time_ns() || pose.t_ns > initial_spline.end_time_ns()) {
      continue;
    }
    const Segment<double> segment = initial_spline.SegmentAtNs(pose.t_ns);
    const int s = segment.index - 1;
    segment_u[s].push_back(segment.u);
    segment_poses[s].push_back(SE3d(SO3d::FromQuaternion(pose.q), pose.p));
    ++used;
  }
  if (used < 2) {
    throw Error("pose fit: fewer than 2 poses fall inside the spline's time range");
  }

  std::vector<std::array<double, kPoseBlockSize>> blocks(layout.num_control_poses);
  for (int i = 0; i < layout.num_control_poses; ++i) PoseToBlock(initial[i], blocks[i].data());

  SE3Manifold manifold;
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (auto& block : blocks) problem.AddParameterBlock(block.data(), kPoseBlockSize, &manifold);
  const double dt_s = 1e-9 * static_cast<double>(layout.dt_ns);
  for (int s = 0; s < num_segments; ++s) {
    if (segment_u[s].empty()) continue;
    problem.AddResidualBlock(internal::NewSegmentPoseCost(std::move(segment_u[s]),
                                                          std::move(segment_poses[s]),
                                                          dt_s,
                                                          options.rotation_weight_m_per_rad,
                                                          options.trajectory),
                             nullptr,
                             blocks[s].data(),
                             blocks[s + 1].data(),
                             blocks[s + 2].data(),
                             blocks[s + 3].data());
  }
  if (options.smoothness_weight > 0.0) {
    for (int i = 1; i + 1 < layout.num_control_poses; ++i) {
      problem.AddResidualBlock(internal::NewSmoothnessPriorCost(options.smoothness_weight),
                               nullptr,
                               blocks[i - 1].data(),
                               blocks[i].data(),
                               blocks[i + 1].data());
    }
  }

  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type =
      ceres::IsSparseLinearAlgebraLibraryTypeAvailable(ceres::SUITE_SPARSE)
          ? ceres::SPARSE_NORMAL_CHOLESKY
          : ceres::DENSE_QR;
  solver_options.max_num_iterations = options.max_iterations;
  solver_options.num_threads = std::max(1, options.num_threads);
  solver_options.function_tolerance = 1e-14;
  solver_options.gradient_tolerance = 1e-14;
  solver_options.parameter_tolerance = 1e-12;
  solver_options.logging_type = ceres::SILENT;
  RoundingFloorStop rounding_floor_stop;
  solver_options.callbacks.push_back(&rounding_floor_stop);
  std::unique_ptr<ProgressCallback> callback;
  if (options.progress) {
    callback = std::make_unique<ProgressCallback>(options.progress);
    solver_options.callbacks.push_back(callback.get());
  }
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, &problem, &summary);

  PoseFitResult result;
  result.layout = layout;
  result.trajectory = options.trajectory;
  result.control_poses.resize(layout.num_control_poses);
  for (int i = 0; i < layout.num_control_poses; ++i) {
    result.control_poses[i] = PoseFromBlock(blocks[i].data());
  }
  result.iterations = static_cast<int>(summary.iterations.size());
  // USER_SUCCESS: stopped at the rounding floor (RoundingFloorStop), converged as well.
  result.converged = summary.termination_type == ceres::CONVERGENCE ||
                     summary.termination_type == ceres::USER_SUCCESS;
  result.solver_report = summary.BriefReport();
  PoseFitErrors(result.MakeSpline(), poses, &result);
  return result;
}

}  // namespace splinecal
