// The progress line of a long Ceres solve (`splinecal fit`, `splinecal calibrate`): one line per
// iteration, handed to the caller's progress function (the front end prints it on stderr unless
// --quiet; docs/conventions.md, "Command line"), and the caller's way to stop it between two
// iterations.
#ifndef SPLINECAL_ESTIMATION_SOLVER_PROGRESS_H_
#define SPLINECAL_ESTIMATION_SOLVER_PROGRESS_H_

#include <ceres/iteration_callback.h>

#include <functional>
#include <string>

namespace splinecal {

class SolverProgressCallback : public ceres::IterationCallback {
 public:
  // Each line reads `prefix` then "iteration  3  cost 1.2e+03  change -4.0e+01  |gradient| ...
  // |step| ...  accepted  0.52 s" (cost change as the decrease Ceres reports, negated).
  SolverProgressCallback(std::function<void(const std::string&)> progress, std::string prefix);

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;

 private:
  std::function<void(const std::string&)> progress_;
  std::string prefix_;
};

// Stops the solve (SOLVER_ABORT, Ceres' USER_FAILURE) as soon as `stop` returns true; asked once
// per iteration, on the thread that called ceres::Solve.
class SolverStopCallback : public ceres::IterationCallback {
 public:
  explicit SolverStopCallback(std::function<bool()> stop);

  ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override;

 private:
  std::function<bool()> stop_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_SOLVER_PROGRESS_H_
