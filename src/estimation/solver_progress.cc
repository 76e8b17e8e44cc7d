#include "splinecal/estimation/solver_progress.h"

#include <utility>

#include "splinecal/string_printf.h"

namespace splinecal {

SolverProgressCallback::SolverProgressCallback(std::function<void(const std::string&)> progress,
                                               std::string prefix)
    : progress_(std::move(progress)), prefix_(std::move(prefix)) {}

ceres::CallbackReturnType SolverProgressCallback::operator()(
    const ceres::IterationSummary& summary) {
  progress_(prefix_ +
            StringPrintf("iteration %2d  cost %.9e  change %+.3e  |gradient| %.3e  |step| %.3e  "
                         "%s  %.2f s",
                         summary.iteration,
                         summary.cost,
                         -summary.cost_change,
                         summary.gradient_max_norm,
                         summary.step_norm,
                         summary.step_is_successful ? "accepted" : "rejected",
                         summary.cumulative_time_in_seconds));
  return ceres::SOLVER_CONTINUE;
}

SolverStopCallback::SolverStopCallback(std::function<bool()> stop) : stop_(std::move(stop)) {}

ceres::CallbackReturnType SolverStopCallback::operator()(const ceres::IterationSummary&) {
  return stop_() ? ceres::SOLVER_ABORT : ceres::SOLVER_CONTINUE;
}

}  // namespace splinecal
