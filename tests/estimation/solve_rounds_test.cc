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

// r = [1e3 (x + y - a); 0.1 (x - y - b)]: the difference x - y is 1e8 times less determined
// than the sum, as a calibration's weakly excited directions are, so Levenberg-Marquardt moves
// along it only once its trust region has grown past ~1e8 (Jacobi-scaled).
struct IllConditioned {
  const double* targets;  // {a, b}, changed between rounds
  template <typename T>
  bool operator()(const T* x, const T* y, T* residual) const {
    residual[0] = T(1e3) * (x[0] + y[0] - T(targets[0]));
    residual[1] = T(0.1) * (x[0] - y[0] - T(targets[1]));
    return true;
  }
};

// Two rounds, the second after the targets moved a little (a re-weighting): the warm second
// round starts from the first's trust region and needs fewer iterations than a cold one; both
// reach the new least-squares solution x = (a + b) / 2, y = (a - b) / 2.
TEST(SolveRounds, AWarmSecondRoundStartsWhereTheFirstEnded) {
  int second_round_iterations[2] = {0, 0};
  for (int warm = 0; warm < 2; ++warm) {
    double targets[2] = {4.0, 2.0};
    double x = 0.0;
    double y = 0.0;
    ceres::Problem problem;
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<IllConditioned, 2, 1, 1>(
                                 new IllConditioned{targets}),
                             nullptr, &x, &y);
    SolverOptions options;
    options.warm_start_rounds = warm == 1;
    SolveRounds rounds(options, /*jacobian_entries=*/1.0);
    const double first_radius = rounds.Solve(&problem, "").iterations.back().trust_region_radius;
    targets[0] = 4.01;
    targets[1] = 2.02;
    const ceres::Solver::Summary& second = rounds.Solve(&problem, "");
    ASSERT_FALSE(rounds.failed());
    // Iteration 0 reports the radius the round started with.
    EXPECT_EQ(second.iterations.front().trust_region_radius,
              warm == 1 ? first_radius : options.initial_trust_region_radius);
    EXPECT_NEAR(x, (4.01 + 2.02) / 2.0, 1e-9);
    EXPECT_NEAR(y, (4.01 - 2.02) / 2.0, 1e-9);
    second_round_iterations[warm] = static_cast<int>(second.iterations.size()) - 1;
  }
  EXPECT_LT(second_round_iterations[1], second_round_iterations[0]);
}

}  // namespace
}  // namespace splinecal
