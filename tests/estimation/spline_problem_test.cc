#include "splinecal/estimation/spline_problem.h"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <vector>

#include "calib/fit_test_data.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/solve_rounds.h"

namespace splinecal {
namespace {

using testing::FitData;
using testing::FitScenario;
using testing::MakeFitData;
using testing::PerturbedControlPoses;

// A residual a user writes without any library code: the position of one control pose equals
// a measured point, sigma 1 mm (the block is {px, py, pz, qx, qy, qz, qw}).
struct ControlPositionResidual {
  explicit ControlPositionResidual(const Eigen::Vector3d& p) : p_(p) {}
  template <typename T>
  bool operator()(const T* block, T* residual) const {
    for (int a = 0; a < 3; ++a) residual[a] = (block[a] - T(p_[a])) / T(1e-3);
    return true;
  }
  Eigen::Vector3d p_;
};

// A ControlPositionResidual at every `step`-th control pose of `truth`.
void AddControlPositions(const SE3Splined& truth, int step, SplineProblem* spline_problem) {
  for (int i = 0; i < truth.num_control_poses(); i += step) {
    spline_problem->problem().AddResidualBlock(
        new ceres::AutoDiffCostFunction<ControlPositionResidual, 3, 7>(
            new ControlPositionResidual(truth.control_pose(i).translation())),
        nullptr,
        spline_problem->control_block(i));
  }
}

// The IMU of a known trajectory plus a few positions (the user's residual) determine the whole
// trajectory: from a perturbed start, the solve recovers the true control poses.
TEST(SplineProblem, ImuPlusAUsersOwnResidualRecoversTheTrajectory) {
  FitScenario scenario;
  scenario.duration_s = 6.0;
  scenario.gyro_bias.setZero();
  scenario.accel_bias.setZero();
  const FitData data = MakeFitData(scenario);
  const KnotLayout layout = data.truth.layout();
  SplineProblem spline_problem(
      layout, PerturbedControlPoses(data.truth, 0.02, 0.02, 7), BiasSpline(), ResidualOptions());
  spline_problem.SetGravity(data.gravity_w);
  ceres::Problem& problem = spline_problem.Reset();
  spline_problem.AddImuResiduals(data.imu, 1e-3, 1e-2);
  AddControlPositions(data.truth, 5, &spline_problem);
  // The IMU cannot see a rotation about gravity: hold the first pose's attitude.
  problem.SetManifold(spline_problem.control_block(0), nullptr);
  problem.SetParameterBlockConstant(spline_problem.control_block(0));
  double* first = spline_problem.control_block(0);
  PoseToBlock(data.truth.control_pose(0), first);
  if (spline_problem.evaluation_callback()) spline_problem.evaluation_callback()->Update();

  SolverOptions solver;
  solver.max_iterations = 30;
  SolveRounds rounds(ToCeresOptions(solver, 0.0, nullptr), {});
  rounds.Solve(&problem, "");
  ASSERT_FALSE(rounds.failed());
  EXPECT_EQ(rounds.rounds(), 1);
  const std::vector<SE3d> solved = spline_problem.ControlPoses();
  double max_position_error = 0.0;
  for (int i = 0; i < layout.num_control_poses; ++i) {
    max_position_error =
        std::max(max_position_error,
                 (solved[i].translation() - data.truth.control_pose(i).translation()).norm());
  }
  // Noise-free data: the solution is the truth to the solver's tolerance.
  EXPECT_LT(max_position_error, 1e-6);
  const ImuResidualStatistics stats = spline_problem.EvaluateImu(data.imu);
  EXPECT_LT(stats.gyro_rms, 1e-7);
  EXPECT_LT(stats.accel_rms, 1e-6);
}

// The bias spline's problem solved with each sparse library (estimation/solve_rounds.h): the
// same steps to rounding, so the same solution; and the library SplineProblem prefers.
TEST(SplineProblem, BothSparseLibrariesReachTheSameSolution) {
  FitScenario scenario;
  scenario.duration_s = 6.0;
  const FitData data = MakeFitData(scenario);
  const KnotLayout layout = data.truth.layout();
  auto solve = [&](SparseLibrary library, std::vector<SE3d>* solved, int* iterations) {
    SplineProblem spline_problem(layout,
                                 PerturbedControlPoses(data.truth, 0.02, 0.02, 7),
                                 BiasSpline(BiasModel::kSpline, layout, 1.0),
                                 ResidualOptions());
    EXPECT_EQ(spline_problem.PreferredSparseLibrary(), SparseLibrary::kEigen);
    spline_problem.SetGravity(data.gravity_w);
    ceres::Problem& problem = spline_problem.Reset();
    spline_problem.AddImuResiduals(data.imu, 1e-3, 1e-2);
    ImuNoise noise = ImuNoise::Adis16448();
    spline_problem.AddBiasRandomWalkResiduals(noise);
    AddControlPositions(data.truth, 5, &spline_problem);
    problem.SetParameterBlockConstant(spline_problem.control_block(0));
    SolverOptions solver;
    solver.max_iterations = 30;
    solver.sparse_library = library;
    const ceres::Solver::Options ceres_options = ToCeresOptions(solver, 0.0, nullptr);
    EXPECT_EQ(ceres_options.sparse_linear_algebra_library_type,
              library == SparseLibrary::kEigen ? ceres::EIGEN_SPARSE : ceres::SUITE_SPARSE);
    SolveRounds rounds(ceres_options, {});
    rounds.Solve(&problem, "");
    ASSERT_FALSE(rounds.failed());
    *solved = spline_problem.ControlPoses();
    *iterations = rounds.iterations();
  };
  std::vector<SE3d> cholmod;
  std::vector<SE3d> eigen;
  int cholmod_iterations = 0;
  int eigen_iterations = 0;
  solve(SparseLibrary::kSuiteSparse, &cholmod, &cholmod_iterations);
  solve(SparseLibrary::kEigen, &eigen, &eigen_iterations);
  EXPECT_EQ(cholmod_iterations, eigen_iterations);
  for (size_t i = 0; i < cholmod.size(); ++i) {
    // Two factorisations of the same normal equations: equal to rounding times the condition.
    EXPECT_LT((cholmod[i].translation() - eigen[i].translation()).norm(), 1e-9) << i;
    EXPECT_LT((cholmod[i].so3().inverse() * eigen[i].so3()).Log().norm(), 1e-9) << i;
  }
  const SplineProblem constant(layout, data.truth.control_poses(), BiasSpline(), {});
  EXPECT_EQ(constant.PreferredSparseLibrary(), SparseLibrary::kSuiteSparse);
}

// r = [x + y; x + y]: the information matrix has rank 1, so no backend reports a covariance.
struct SumResidual {
  template <typename T>
  bool operator()(const T* x, const T* y, T* residual) const {
    residual[0] = x[0] + y[0];
    residual[1] = T(2.0) * (x[0] + y[0]);
    return true;
  }
};

TEST(MarginalCovariance, EveryBackendRefusesASingularProblem) {
  double x = 1.0;
  double y = 2.0;
  ceres::Problem problem;
  problem.AddResidualBlock(
      new ceres::AutoDiffCostFunction<SumResidual, 2, 1, 1>(new SumResidual), nullptr, &x, &y);
  for (CovarianceBackend backend : {CovarianceBackend::kCeres,
                                    CovarianceBackend::kSchur,
                                    CovarianceBackend::kCeresUncompressed}) {
    MarginalCovarianceOptions options;
    options.backend = backend;
    EXPECT_FALSE(ComputeMarginalCovariance(&problem, {&x}, options).ok)
        << static_cast<int>(backend);
  }
}

// The three backends compute the same (J^T J)^-1 blocks on a spline problem with a bias spline,
// gravity on its manifold and control poses on SE(3).
TEST(MarginalCovariance, BackendsAgreeWithCeresCovariance) {
  FitScenario scenario;
  scenario.duration_s = 4.0;
  const FitData data = MakeFitData(scenario);
  const KnotLayout layout = data.truth.layout();
  SplineProblem spline_problem(layout,
                               data.truth.control_poses(),
                               BiasSpline(BiasModel::kSpline, layout, 1.0),
                               ResidualOptions());
  spline_problem.SetGravity(data.gravity_w);
  ceres::Problem& problem = spline_problem.Reset(/*hold_first_pose=*/true);
  spline_problem.AddImuResiduals(data.imu, 1e-3, 1e-2);
  ImuNoise noise = ImuNoise::Adis16448();
  spline_problem.AddBiasRandomWalkResiduals(noise);
  for (int i = 0; i < layout.num_control_poses; i += 4) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ControlPositionResidual, 3, 7>(
            new ControlPositionResidual(data.truth.control_pose(i).translation())),
        nullptr,
        spline_problem.control_block(i));
  }
  const std::vector<const double*> blocks = {spline_problem.gravity(),
                                             spline_problem.gyro_bias(1),
                                             spline_problem.accel_bias(2),
                                             spline_problem.control_block(9)};
  MarginalCovarianceOptions options;
  options.backend = CovarianceBackend::kCeresUncompressed;
  const MarginalCovariance reference = ComputeMarginalCovariance(&problem, blocks, options);
  ASSERT_TRUE(reference.ok);
  ASSERT_EQ(reference.covariance.rows(), 2 + 3 + 3 + 6);
  for (CovarianceBackend backend : {CovarianceBackend::kCeres, CovarianceBackend::kSchur}) {
    options.backend = backend;
    const MarginalCovariance other = ComputeMarginalCovariance(&problem, blocks, options);
    ASSERT_TRUE(other.ok) << other.method;
    const Eigen::MatrixXd& C = reference.covariance;
    for (int r = 0; r < C.rows(); ++r) {
      for (int c = 0; c < C.cols(); ++c) {
        // Equal to rounding times the condition number.
        EXPECT_NEAR(other.covariance(r, c), C(r, c), 1e-7 * std::sqrt(C(r, r) * C(c, c)))
            << other.method << " " << r << "," << c;
      }
    }
  }
  // kAuto picks ceres::Covariance on a problem this small, the sparse factorisation of the
  // compressed information with a zero entry budget.
  options.backend = CovarianceBackend::kAuto;
  EXPECT_EQ(ComputeMarginalCovariance(&problem, blocks, options).method.rfind("ceres", 0), 0u);
  options.max_ceres_covariance_entries = 0.0;
  EXPECT_NE(ComputeMarginalCovariance(&problem, blocks, options).method.find("sparse LDL^T"),
            std::string::npos);
}

}  // namespace
}  // namespace splinecal
