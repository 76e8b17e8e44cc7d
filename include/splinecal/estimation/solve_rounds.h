// Solver settings with one shape for every estimate (fit, calibrate, a user's own), and the
// rounds of a solve: estimates whose residuals must be re-attached or re-weighted after a solve
// (a time offset moved samples across knots, the pixel noise was re-estimated) solve again,
// and report the rounds as one solve (time, iterations, first initial cost, last summary).
#ifndef SPLINECAL_ESTIMATION_SOLVE_ROUNDS_H_
#define SPLINECAL_ESTIMATION_SOLVE_ROUNDS_H_

#include <ceres/iteration_callback.h>
#include <ceres/problem.h>
#include <ceres/solver.h>

#include <functional>
#include <string>
#include <vector>

namespace splinecal {

// Ceres' linear solver for the Levenberg-Marquardt steps.
enum class LinearSolver {
  // kSparseNormalCholesky, or kSparseSchur when the Jacobian would exceed
  // SolverOptions::max_normal_cholesky_jacobian_entries (long recordings).
  kAuto,
  // SPARSE_NORMAL_CHOLESKY (SuiteSparse). Ceres 2.1 appends the LM diagonal to the Jacobian by
  // reallocating it on the first step: for a moment it holds two copies of J.
  kSparseNormalCholesky,
  // SPARSE_SCHUR: eliminates an independent set of control poses; no copy of J, similar speed.
  kSparseSchur,
  // DENSE_SCHUR: eliminates the same independent set and keeps the reduced system dense. For a
  // reduced system that is dense anyway -- the intrinsics with every target point free, where
  // each view couples its ~100 points' offsets with each other and with the intrinsics -- it
  // spares the sparse one's per-cell hash lookup (on EuRoC's imu_april, 1302 views and 1275
  // offsets: 14.7 s of solving with SPARSE_SCHUR, 8.6 s with DENSE_SCHUR, the same solution).
  kDenseSchur,
};

// Ceres' sparse linear algebra for kSparseNormalCholesky's factorisation (docs/performance.md
// "Calibrate at Kalibr's knot density in under 20 s": calibrate on EuRoC at 0.01 s knots, 0.25 s
// per iteration with CHOLMOD, 0.14 s with Eigen; fit of V1_01 with constant biases, 0.35 s with
// CHOLMOD, 0.62 s with Eigen).
enum class SparseLibrary {
  // kSuiteSparse, unless the estimate knows its structure better (SplineProblem's
  // PreferredSparseLibrary, which fit and calibrate ask).
  kAuto,
  // CHOLMOD's supernodal Cholesky: dense kernels on column blocks, fastest on a banded matrix
  // (control poses and constant biases).
  kSuiteSparse,
  // Eigen's simplicial LDL^T: fastest when a bias spline's control points -- each coupled to the
  // hundreds of control poses of its support -- interleave with the poses and leave CHOLMOD
  // supernodes of a few columns, whose per-block overhead then dominates.
  kEigen,
};

struct SolverOptions {
  int max_iterations = 50;  // per round
  int max_rounds = 4;       // solves at most (each after a rebuild the estimate asked for)
  int num_threads = 1;
  double function_tolerance = 1e-10;
  double gradient_tolerance = 1e-12;
  double parameter_tolerance = 1e-10;
  // Levenberg-Marquardt's first trust region (Ceres' default 1e4).
  double initial_trust_region_radius = 1e4;
  // Rounds after the first start their trust region where the previous round's ended. A round
  // re-solves the same problem from the previous solution (re-weighted, re-windowed); restarted
  // at 1e4, calibrate's rounds spent ~12 iterations each growing the radius 3x per accepted step
  // (every step had a gain ratio ~1.000: the model was never the limit) before Gauss-Newton
  // steps were allowed (d438137 in docs/performance.md "Calibrate at Kalibr's knot density in
  // under 20 s"). false: every round starts at initial_trust_region_radius.
  bool warm_start_rounds = true;
  LinearSolver linear_solver = LinearSolver::kAuto;
  SparseLibrary sparse_library = SparseLibrary::kAuto;
  // kAuto switches to SPARSE_SCHUR above this many Jacobian entries (8e6: 64 MB, ~2.7 minutes
  // of 200 Hz IMU), where SPARSE_NORMAL_CHOLESKY's transient second copy of J dominates memory.
  double max_normal_cholesky_jacobian_entries = 8e6;
  // One line per solver iteration (empty: silent).
  std::function<void(const std::string&)> progress;
  // Asked once per solver iteration (empty: never); true stops the solve at once with Ceres'
  // USER_FAILURE, which the estimates report as a failed solve. The Python module's Ctrl-C.
  std::function<bool()> stop;
};

// Throws splinecal::Error (naming `what`) for values no solve can use.
void CheckSolverOptions(const SolverOptions& options);

// The Ceres options for `options`; jacobian_entries (an estimate) chooses the linear solver
// under LinearSolver::kAuto, and *linear_solver_name (may be nullptr) names the one chosen.
ceres::Solver::Options ToCeresOptions(const SolverOptions& options,
                                      double jacobian_entries,
                                      std::string* linear_solver_name);

// How a (multi-round) solve went, in every estimate's result.
struct SolveSummary {
  int rounds = 0;
  int iterations = 0;         // over all rounds
  double initial_cost = 0.0;  // 1/2 |r|^2 at the start of the first round
  double final_cost = 0.0;    // at the end of the last
  double solve_time_s = 0.0;  // wall time in ceres::Solve
  std::string termination;    // Ceres' termination message of the last round
  std::string report;         // Ceres' FullReport of the last round (timings per phase)
  std::string linear_solver;  // the Ceres linear solver used
};

class SolveRounds {
 public:
  SolveRounds(ceres::Solver::Options options,
              std::function<void(const std::string&)> progress,
              std::function<bool()> stop = {},
              bool warm_start_rounds = true)
      : options_(std::move(options)),
        progress_(std::move(progress)),
        stop_(std::move(stop)),
        warm_start_rounds_(warm_start_rounds) {}
  // ToCeresOptions(options, jacobian_entries, ...) with options.progress and options.stop.
  SolveRounds(const SolverOptions& options, double jacobian_entries);

  // Solves `problem` as the next round (with warm_start_rounds, from the trust region the last
  // round ended with); progress lines start with `progress_prefix`;
  // `callbacks` are added to this round's iteration callbacks. Returns the round's summary.
  const ceres::Solver::Summary& Solve(ceres::Problem* problem,
                                      const std::string& progress_prefix,
                                      const std::vector<ceres::IterationCallback*>& callbacks = {});

  int rounds() const { return rounds_; }
  int iterations() const { return iterations_; }
  double initial_cost() const { return initial_cost_; }  // of the first round
  double solve_time_s() const { return solve_time_s_; }  // wall time in ceres::Solve, all rounds
  const ceres::Solver::Summary& last() const { return last_; }
  // The last round failed (Ceres reported FAILURE or an unusable solution).
  bool failed() const;
  // "the solver stopped after N iterations without converging (...)", or "" when it converged.
  std::string NoConvergenceWarning() const;
  // The rounds so far as one solve.
  SolveSummary Summary() const;

 private:
  std::string linear_solver_;  // before options_: its constructor writes it
  ceres::Solver::Options options_;
  std::function<void(const std::string&)> progress_;
  std::function<bool()> stop_;
  bool warm_start_rounds_ = true;
  ceres::Solver::Summary last_;
  int rounds_ = 0;
  int iterations_ = 0;
  double initial_cost_ = 0.0;
  double solve_time_s_ = 0.0;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_SOLVE_ROUNDS_H_
