#include "splinecal/estimation/solve_rounds.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

namespace splinecal {
namespace {

// r(x) = 10 - x: Levenberg-Marquardt needs a few iterations from x = 0 to meet the tolerances.
struct Offset {
  template <typename T>
  bool operator()(const T* x, T* residual) const {
    residual[0] = T(10.0) - x[0];
    return true;
  }
};

ceres::Problem* AddOffsetProblem(ceres::Problem* problem, double* x) {
  problem->AddResidualBlock(new ceres::AutoDiffCostFunction<Offset, 1, 1>(new Offset), nullptr, x);
  return problem;
}

TEST(SolveRounds, StopAbortsTheSolveAsAFailure) {
  SolverOptions options;
  int asked = 0;
  options.stop = [&asked] { return ++asked >= 1; };
  SolveRounds rounds(options, /*jacobian_entries=*/1.0);
  ceres::Problem problem;
  double x = 0.0;
  rounds.Solve(AddOffsetProblem(&problem, &x), "test: ");
  EXPECT_EQ(asked, 1);  // asked once, at iteration 0, and never again
  EXPECT_EQ(rounds.last().termination_type, ceres::USER_FAILURE);
  EXPECT_TRUE(rounds.failed());
}

TEST(SolveRounds, StopThatNeverFiresLeavesTheSolveAlone) {
  SolverOptions options;
  int asked = 0;
  options.stop = [&asked] {
    ++asked;
    return false;
  };
  SolveRounds rounds(options, /*jacobian_entries=*/1.0);
  ceres::Problem problem;
  double x = 0.0;
  rounds.Solve(AddOffsetProblem(&problem, &x), "test: ");
  EXPECT_GE(asked, 2);
  EXPECT_FALSE(rounds.failed());
  EXPECT_NEAR(x, 10.0, 1e-9);
}

}  // namespace
}  // namespace splinecal
