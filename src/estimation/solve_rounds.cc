#include "splinecal/estimation/solve_rounds.h"

#include <ceres/ceres.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>

#include "splinecal/error.h"
#include "splinecal/estimation/solver_progress.h"

namespace splinecal {

void CheckSolverOptions(const SolverOptions& o) {
  auto positive = [](double value, const std::string& name) {
    if (!(value > 0.0) || !std::isfinite(value)) {
      throw Error(name + " must be a positive number, got " + std::to_string(value));
    }
  };
  positive(o.initial_trust_region_radius, "initial trust region radius");
  if (o.max_iterations < 1) throw Error("max iterations must be >= 1");
  if (o.max_rounds < 1) throw Error("solver rounds must be >= 1");
  if (o.num_threads < 1) throw Error("threads must be >= 1");
}

ceres::Solver::Options ToCeresOptions(const SolverOptions& options,
                                      double jacobian_entries,
                                      std::string* linear_solver_name) {
  ceres::Solver::Options ceres_options;
  const bool schur = options.linear_solver == LinearSolver::kSparseSchur ||
                     (options.linear_solver == LinearSolver::kAuto &&
                      jacobian_entries > options.max_normal_cholesky_jacobian_entries);
  if (options.linear_solver == LinearSolver::kDenseSchur) {
    ceres_options.linear_solver_type = ceres::DENSE_SCHUR;
  } else {
    ceres_options.linear_solver_type = schur ? ceres::SPARSE_SCHUR : ceres::SPARSE_NORMAL_CHOLESKY;
  }
  if (ceres_options.linear_solver_type == ceres::SPARSE_NORMAL_CHOLESKY &&
      options.sparse_library == SparseLibrary::kEigen) {
    ceres_options.sparse_linear_algebra_library_type = ceres::EIGEN_SPARSE;
  }
  if (linear_solver_name != nullptr) {
    *linear_solver_name = ceres::LinearSolverTypeToString(ceres_options.linear_solver_type);
  }
  ceres_options.num_threads = options.num_threads;
  ceres_options.max_num_iterations = options.max_iterations;
  ceres_options.function_tolerance = options.function_tolerance;
  ceres_options.gradient_tolerance = options.gradient_tolerance;
  ceres_options.parameter_tolerance = options.parameter_tolerance;
  ceres_options.initial_trust_region_radius = options.initial_trust_region_radius;
  ceres_options.logging_type = ceres::SILENT;
  return ceres_options;
}

const ceres::Solver::Summary& SolveRounds::Solve(
    ceres::Problem* problem,
    const std::string& progress_prefix,
    const std::vector<ceres::IterationCallback*>& callbacks) {
  ceres::Solver::Options round_options = options_;
  std::unique_ptr<SolverProgressCallback> progress;
  if (progress_) {
    progress = std::make_unique<SolverProgressCallback>(progress_, progress_prefix);
    round_options.callbacks.push_back(progress.get());
  }
  std::unique_ptr<SolverStopCallback> stop;
  if (stop_) {
    stop = std::make_unique<SolverStopCallback>(stop_);
    round_options.callbacks.push_back(stop.get());
  }
  for (ceres::IterationCallback* callback : callbacks) round_options.callbacks.push_back(callback);
  if (warm_start_rounds_ && rounds_ > 0 && !last_.iterations.empty()) {
    round_options.initial_trust_region_radius =
        std::min(last_.iterations.back().trust_region_radius, options_.max_trust_region_radius);
  }
  const auto start = std::chrono::steady_clock::now();
  ceres::Solve(round_options, problem, &last_);
  solve_time_s_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  iterations_ += static_cast<int>(last_.iterations.size()) - 1;
  if (rounds_ == 0) initial_cost_ = last_.initial_cost;
  ++rounds_;
  return last_;
}

SolveRounds::SolveRounds(const SolverOptions& options, double jacobian_entries)
    : options_(ToCeresOptions(options, jacobian_entries, &linear_solver_)),
      progress_(options.progress),
      stop_(options.stop),
      warm_start_rounds_(options.warm_start_rounds) {}

SolveSummary SolveRounds::Summary() const {
  SolveSummary summary;
  summary.rounds = rounds_;
  summary.iterations = iterations_;
  summary.initial_cost = initial_cost_;
  summary.final_cost = last_.final_cost;
  summary.solve_time_s = solve_time_s_;
  summary.termination = last_.message;
  summary.report = last_.FullReport();
  summary.linear_solver = linear_solver_.empty()
                              ? ceres::LinearSolverTypeToString(options_.linear_solver_type)
                              : linear_solver_;
  return summary;
}

bool SolveRounds::failed() const {
  return last_.termination_type == ceres::FAILURE || !last_.IsSolutionUsable();
}

std::string SolveRounds::NoConvergenceWarning() const {
  if (last_.termination_type != ceres::NO_CONVERGENCE) return "";
  return "the solver stopped after " + std::to_string(iterations_) +
         " iterations without converging (" + last_.message + ")";
}

}  // namespace splinecal
