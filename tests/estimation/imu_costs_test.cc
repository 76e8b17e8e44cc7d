#include "splinecal/estimation/detail/imu_costs.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <memory>
#include <random>
#include <vector>

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/autodiff_costs.h"

namespace splinecal {
namespace {

// The issue: analytic and autodiff residuals agree to 1e-9 in value and Jacobian. Both are exact
// derivatives of the same double-precision function; they differ by rounding only (~1e-14 on
// the O(10) entries here), so 1e-9 relative to max(1, |entry|) has a wide margin.
constexpr double kAutoDiffTolerance = 1e-9;
// ceres::GradientChecker against its own numeric differentiation (central differences, relative
// step 1e-6): truncation ~1e-12 relative, rounding ~1e-10; 1e-6 is Ceres' customary bound.
constexpr double kGradientCheckerPrecision = 1e-6;
// Stacked vs per-sample and shared vs local knots run the same arithmetic.
constexpr double kSameArithmeticTolerance = 1e-13;

constexpr double kDtS = 0.1;

// Four control poses with large knot deltas (rotation steps ~0.6 rad, translation ~1 m), in
// blocks {px, py, pz, qx, qy, qz, qw}.
std::vector<std::array<double, 7>> RandomPoseBlocks(int count, uint64_t seed) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<std::array<double, 7>> blocks(count);
  SE3d T = SE3d::Exp((Vector6d() << 1.0, -2.0, 0.5, 0.3, -1.2, 2.0).finished());
  for (int i = 0; i < count; ++i) {
    Vector6d xi;
    for (int k = 0; k < 3; ++k) xi[k] = normal(rng);
    for (int k = 3; k < 6; ++k) xi[k] = 0.35 * normal(rng);
    T = T * SE3d::Exp(xi);
    PoseToBlock(T, blocks[i].data());
  }
  return blocks;
}

struct Blocks {
  std::vector<std::array<double, 7>> poses;
  std::vector<std::array<double, 3>> biases;
  std::array<double, 3> gravity = {0.3, -0.2, -9.8};
  // parameters in cost-function order: poses, biases, [gravity]
  std::vector<double*> Pointers(int bias_blocks, bool with_gravity) {
    std::vector<double*> p;
    for (int k = 0; k < 4; ++k) p.push_back(poses[k].data());
    for (int j = 0; j < bias_blocks; ++j) p.push_back(biases[j].data());
    if (with_gravity) p.push_back(gravity.data());
    return p;
  }
};

Blocks MakeBlocks(uint64_t seed) {
  Blocks b;
  b.poses = RandomPoseBlocks(4, seed);
  std::mt19937 rng(static_cast<unsigned>(seed + 100));
  std::normal_distribution<double> normal(0.0, 0.2);
  b.biases.resize(4);
  for (auto& bias : b.biases) {
    for (double& v : bias) v = normal(rng);
  }
  return b;
}

ImuResidualSample MakeSample(double u, uint64_t seed, bool spline_bias) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> normal(0.0, 1.0);
  ImuResidualSample sample;
  sample.u = u;
  sample.measured = Eigen::Vector3d(normal(rng), normal(rng), 9.0 + normal(rng));
  if (spline_bias) sample.bias_weights = BiasSplineWeights(0.37 + 0.1 * u);
  return sample;
}

struct Evaluation {
  std::vector<double> residuals;
  std::vector<std::vector<double>> jacobians;
};

Evaluation Evaluate(const ceres::CostFunction& cost, const std::vector<double*>& parameters) {
  Evaluation e;
  e.residuals.assign(cost.num_residuals(), 0.0);
  const std::vector<int32_t>& sizes = cost.parameter_block_sizes();
  e.jacobians.resize(sizes.size());
  std::vector<double*> jacobian_pointers;
  for (size_t i = 0; i < sizes.size(); ++i) {
    e.jacobians[i].assign(cost.num_residuals() * sizes[i], 0.0);
    jacobian_pointers.push_back(e.jacobians[i].data());
  }
  EXPECT_TRUE(cost.Evaluate(parameters.data(), e.residuals.data(), jacobian_pointers.data()));
  return e;
}

double MaxRelativeDifference(const std::vector<double>& a, const std::vector<double>& b) {
  EXPECT_EQ(a.size(), b.size());
  double worst = 0.0;
  for (size_t k = 0; k < a.size(); ++k) {
    worst = std::max(worst, std::abs(a[k] - b[k]) / std::max(1.0, std::abs(b[k])));
  }
  return worst;
}

void ExpectSame(const Evaluation& a, const Evaluation& b, double tolerance) {
  EXPECT_LE(MaxRelativeDifference(a.residuals, b.residuals), tolerance);
  ASSERT_EQ(a.jacobians.size(), b.jacobians.size());
  for (size_t i = 0; i < a.jacobians.size(); ++i) {
    EXPECT_LE(MaxRelativeDifference(a.jacobians[i], b.jacobians[i]), tolerance) << "block " << i;
  }
}

std::vector<const ceres::Manifold*> Manifolds(int bias_blocks,
                                              bool with_gravity,
                                              const ceres::Manifold* pose,
                                              const ceres::Manifold* gravity) {
  std::vector<const ceres::Manifold*> manifolds(4, pose);
  for (int j = 0; j < bias_blocks; ++j) manifolds.push_back(nullptr);
  if (with_gravity) manifolds.push_back(gravity);
  return manifolds;
}

// The residual segment `index` of the test spline (knot spacing kDtS) with noise std `sigma`.
ImuResidualSegment TestSegment(int index,
                               double sigma = 1.0,
                               TrajectoryModel model = TrajectoryModel::kSE3) {
  ImuResidualSegment segment;
  segment.segment_index = index;
  segment.dt_s = kDtS;
  segment.sigma = sigma;
  segment.model = model;
  return segment;
}

// Cost<1> (constant bias) or Cost<4> (bias spline), as `bias_blocks` says, from `args`.
template <template <int> class Cost, typename... Args>
std::unique_ptr<ceres::CostFunction> MakeCost(int bias_blocks, const Args&... args) {
  if (bias_blocks == 1) return std::make_unique<Cost<1>>(args...);
  return std::make_unique<Cost<4>>(args...);
}

// The segment positions probed: both ends and the inside.
const double kUs[] = {0.0, 0.23, 0.5, 0.81, 1.0};

// The analytic Cost<1> and Cost<4> against their automatic-differentiation twins (new_autodiff,
// testing/autodiff_costs.h) at every kUs; the accelerometer's cost has the gravity block too.
template <template <int> class Cost>
void ExpectAnalyticMatchesAutoDiff(ceres::CostFunction* (*new_autodiff)(int,
                                                                        const ImuResidualSegment&,
                                                                        const ImuResidualSample&),
                                   bool with_gravity) {
  for (int bias_blocks : {1, 4}) {
    for (double u : kUs) {
      Blocks blocks = MakeBlocks(with_gravity ? 4 : 3);
      const ImuResidualSegment segment = TestSegment(5);
      const ImuResidualSample sample = MakeSample(u, with_gravity ? 10 : 9, bias_blocks == 4);
      const std::unique_ptr<ceres::CostFunction> analytic =
          MakeCost<Cost>(bias_blocks, segment, sample);
      std::unique_ptr<ceres::CostFunction> autodiff(new_autodiff(bias_blocks, segment, sample));
      const std::vector<double*> p = blocks.Pointers(bias_blocks, with_gravity);
      ExpectSame(Evaluate(*analytic, p), Evaluate(*autodiff, p), kAutoDiffTolerance);
    }
  }
}

TEST(GyroCostFunction, AnalyticMatchesAutoDiffForBothBiasModels) {
  ExpectAnalyticMatchesAutoDiff<GyroCostFunction>(&testing::NewAutoDiffGyroCost, false);
}

TEST(AccelCostFunction, AnalyticMatchesAutoDiffForBothBiasModels) {
  ExpectAnalyticMatchesAutoDiff<AccelCostFunction>(&testing::NewAutoDiffAccelCost, true);
}

// Central differences along the tangent of every block (through its manifold's Plus), against
// the cost function's ambient Jacobian times PlusJacobian: the check GradientChecker does, with
// an error bound relative to the largest entry of the block (Ceres' per-entry relative error
// cannot accept the exact zeros of the gyro Jacobian, e.g. d w_s / d R_{i-1}).
double MaxTangentJacobianError(const ceres::CostFunction& cost,
                               const std::vector<double*>& parameters,
                               const std::vector<const ceres::Manifold*>& manifolds) {
  constexpr double kStep = 1e-6;
  const Evaluation analytic = Evaluate(cost, parameters);
  const int rows = cost.num_residuals();
  double worst = 0.0;
  for (size_t i = 0; i < parameters.size(); ++i) {
    const int ambient = cost.parameter_block_sizes()[i];
    const int tangent = manifolds[i] != nullptr ? manifolds[i]->TangentSize() : ambient;
    Eigen::MatrixXd plus_jacobian = Eigen::MatrixXd::Identity(ambient, tangent);
    if (manifolds[i] != nullptr) {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> pj(ambient, tangent);
      manifolds[i]->PlusJacobian(parameters[i], pj.data());
      plus_jacobian = pj;
    }
    const Eigen::MatrixXd J_ambient =
        Eigen::Map<const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
            analytic.jacobians[i].data(), rows, ambient);
    const Eigen::MatrixXd J_tangent = J_ambient * plus_jacobian;
    Eigen::MatrixXd J_numeric(rows, tangent);
    const std::vector<double> original(parameters[i], parameters[i] + ambient);
    for (int c = 0; c < tangent; ++c) {
      std::vector<double> r_plus(rows);
      std::vector<double> r_minus(rows);
      for (double sign : {1.0, -1.0}) {
        Eigen::VectorXd delta = Eigen::VectorXd::Zero(tangent);
        delta[c] = sign * kStep;
        if (manifolds[i] != nullptr) {
          manifolds[i]->Plus(original.data(), delta.data(), parameters[i]);
        } else {
          for (int k = 0; k < ambient; ++k) parameters[i][k] = original[k] + delta[k];
        }
        cost.Evaluate(parameters.data(), sign > 0 ? r_plus.data() : r_minus.data(), nullptr);
      }
      std::copy(original.begin(), original.end(), parameters[i]);
      for (int r = 0; r < rows; ++r) J_numeric(r, c) = (r_plus[r] - r_minus[r]) / (2.0 * kStep);
    }
    const double scale = std::max(1.0, J_tangent.cwiseAbs().maxCoeff());
    worst = std::max(worst, (J_tangent - J_numeric).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

// Central differences with step 1e-6: truncation ~1e-12 |f'''|, rounding ~1e-16 |f| / 1e-6;
// relative to the largest Jacobian entry, ~1e-8 at worst here.
constexpr double kTangentJacobianTolerance = 1e-6;

TEST(ImuCostFunctions, PassCeresGradientCheckerThroughTheManifolds) {
  const SE3Manifold se3;
  const GravityManifold gravity;
  for (int bias_blocks : {1, 4}) {
    for (double u : {0.0, 0.4, 1.0}) {
      Blocks blocks = MakeBlocks(5);
      const ImuResidualSegment segment = TestSegment(2, 0.02);  // weighted, as in a fit
      const ImuResidualSample sample = MakeSample(u, 12, bias_blocks == 4);
      const std::unique_ptr<ceres::CostFunction> gyro =
          MakeCost<GyroCostFunction>(bias_blocks, segment, sample);
      const std::unique_ptr<ceres::CostFunction> accel =
          MakeCost<AccelCostFunction>(bias_blocks, segment, sample);
      const std::vector<const ceres::Manifold*> gyro_manifolds =
          Manifolds(bias_blocks, false, &se3, &gravity);
      const std::vector<const ceres::Manifold*> accel_manifolds =
          Manifolds(bias_blocks, true, &se3, &gravity);
      // Our own tangent-space check first (it accepts exact zeros), then Ceres' GradientChecker.
      EXPECT_LE(MaxTangentJacobianError(*gyro, blocks.Pointers(bias_blocks, false), gyro_manifolds),
                kTangentJacobianTolerance);
      EXPECT_LE(
          MaxTangentJacobianError(*accel, blocks.Pointers(bias_blocks, true), accel_manifolds),
          kTangentJacobianTolerance);
      // At u = 1 the segment's pose is P_2 Exp(Omega_3 / 6): every Jacobian with respect to
      // P_0 is exactly zero, which GradientChecker's per-entry relative error cannot pass.
      if (u == 1.0) continue;
      ceres::NumericDiffOptions numeric;
      ceres::GradientChecker gyro_checker(gyro.get(), &gyro_manifolds, numeric);
      ceres::GradientChecker accel_checker(accel.get(), &accel_manifolds, numeric);
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(gyro_checker.Probe(
          blocks.Pointers(bias_blocks, false).data(), kGradientCheckerPrecision, &results))
          << results.error_log;
      EXPECT_TRUE(accel_checker.Probe(
          blocks.Pointers(bias_blocks, true).data(), kGradientCheckerPrecision, &results))
          << results.error_log;
    }
  }
}

// The split SO(3) x R^3 model's accelerometer residual (ImuResidualSegment::model): analytic
// against its autodiff twin, through the manifolds, and stacked per segment; it is another
// residual than the coupled model's on the same blocks.
TEST(AccelCostFunction, SplitModelMatchesAutoDiffAndPassesGradientChecker) {
  const SE3Manifold se3;
  const GravityManifold gravity;
  for (int bias_blocks : {1, 4}) {
    for (double u : kUs) {
      Blocks blocks = MakeBlocks(14);
      // Unweighted: with these knot steps (~1 m per 0.1 s) a_w reaches ~100 m/s^2, and at
      // sigma 0.02 the residual's ~1e4 gives central differences a rounding error of
      // ~1e-16 |r| / 1e-6 ~ 1e-6 on blocks whose Jacobian is exactly zero (P_0 at u = 0).
      const ImuResidualSegment segment = TestSegment(5, 1.0, TrajectoryModel::kSplitSO3R3);
      const ImuResidualSample sample = MakeSample(u, 15, bias_blocks == 4);
      ImuResidualSegment coupled_segment = segment;
      coupled_segment.model = TrajectoryModel::kSE3;
      const std::unique_ptr<ceres::CostFunction> analytic =
          MakeCost<AccelCostFunction>(bias_blocks, segment, sample);
      const std::unique_ptr<ceres::CostFunction> stacked = MakeCost<AccelSegmentCostFunction>(
          bias_blocks, segment, std::vector<ImuResidualSample>{sample, sample});
      const std::unique_ptr<ceres::CostFunction> coupled =
          MakeCost<AccelCostFunction>(bias_blocks, coupled_segment, sample);
      std::unique_ptr<ceres::CostFunction> autodiff(
          testing::NewAutoDiffAccelCost(bias_blocks, segment, sample));
      const std::vector<double*> p = blocks.Pointers(bias_blocks, true);
      const Evaluation split = Evaluate(*analytic, p);
      ExpectSame(split, Evaluate(*autodiff, p), kAutoDiffTolerance);
      EXPECT_GT(MaxRelativeDifference(split.residuals, Evaluate(*coupled, p).residuals), 1e-6);
      const Evaluation rows = Evaluate(*stacked, p);
      for (int r = 0; r < 3; ++r) {
        EXPECT_EQ(rows.residuals[r], split.residuals[r]);
        EXPECT_EQ(rows.residuals[3 + r], split.residuals[r]);
      }
      const std::vector<const ceres::Manifold*> manifolds =
          Manifolds(bias_blocks, true, &se3, &gravity);
      EXPECT_LE(MaxTangentJacobianError(*analytic, p, manifolds), kTangentJacobianTolerance);
      if (u == 1.0) continue;  // exact zeros on P_0 (see above)
      ceres::GradientChecker checker(analytic.get(), &manifolds, ceres::NumericDiffOptions());
      ceres::GradientChecker::ProbeResults results;
      EXPECT_TRUE(checker.Probe(p.data(), kGradientCheckerPrecision, &results))
          << results.error_log;
    }
  }
}

TEST(ImuSegmentCostFunctions, StackTheSampleResidualsRowByRow) {
  Blocks blocks = MakeBlocks(6);
  const ImuResidualSegment segment = TestSegment(3, 0.05);
  std::vector<ImuResidualSample> samples;
  for (int s = 0; s < 5; ++s) samples.push_back(MakeSample(kUs[s], 20 + s, true));
  const GyroSegmentCostFunction<4> gyro_stack(segment, samples);
  const AccelSegmentCostFunction<4> accel_stack(segment, samples);
  const Evaluation gyro_all = Evaluate(gyro_stack, blocks.Pointers(4, false));
  const Evaluation accel_all = Evaluate(accel_stack, blocks.Pointers(4, true));
  for (int s = 0; s < 5; ++s) {
    const Evaluation gyro_one =
        Evaluate(GyroCostFunction<4>(segment, samples[s]), blocks.Pointers(4, false));
    const Evaluation accel_one =
        Evaluate(AccelCostFunction<4>(segment, samples[s]), blocks.Pointers(4, true));
    for (const auto& [all, one] :
         {std::pair(&gyro_all, &gyro_one), std::pair(&accel_all, &accel_one)}) {
      for (int r = 0; r < 3; ++r) {
        EXPECT_NEAR(all->residuals[3 * s + r], one->residuals[r], kSameArithmeticTolerance);
      }
      for (size_t i = 0; i < one->jacobians.size(); ++i) {
        const size_t size = one->jacobians[i].size() / 3;
        for (size_t c = 0; c < 3 * size; ++c) {
          EXPECT_NEAR(
              all->jacobians[i][3 * s * size + c], one->jacobians[i][c], kSameArithmeticTolerance);
        }
      }
    }
  }
}

TEST(ImuCostFunctions, SharedKnotCachesGiveTheLocalAnswerAndAreNotUsedWhenStale) {
  // A spline of 7 control poses; segment 3 uses control poses 2..5.
  std::vector<std::array<double, 7>> poses = RandomPoseBlocks(7, 8);
  std::vector<double*> pointers;
  for (auto& pose : poses) pointers.push_back(pose.data());
  SplineEvaluationCallback callback(pointers, 0, 100'000'000);
  callback.PrepareForEvaluation(true, true);

  Blocks blocks = MakeBlocks(9);
  for (int k = 0; k < 4; ++k) blocks.poses[k] = poses[2 + k];
  ImuResidualSegment local_segment;
  local_segment.segment_index = 3;
  local_segment.dt_s = 0.1;
  ImuResidualSegment shared_segment = local_segment;
  shared_segment.shared = &callback;
  const ImuResidualSample sample = MakeSample(0.6, 13, false);

  EXPECT_TRUE(callback.Matches(2, blocks.Pointers(1, true).data()));
  ExpectSame(Evaluate(AccelCostFunction<1>(shared_segment, sample), blocks.Pointers(1, true)),
             Evaluate(AccelCostFunction<1>(local_segment, sample), blocks.Pointers(1, true)),
             kSameArithmeticTolerance);
  ExpectSame(Evaluate(GyroCostFunction<1>(shared_segment, sample), blocks.Pointers(1, false)),
             Evaluate(GyroCostFunction<1>(local_segment, sample), blocks.Pointers(1, false)),
             kSameArithmeticTolerance);

  // Parameters that differ from the callback's (as under numeric differentiation): the cost
  // function must compute its own knots, not use the stale cache.
  blocks.poses[1][0] += 0.25;
  EXPECT_FALSE(callback.Matches(2, blocks.Pointers(1, true).data()));
  const Evaluation stale_shared =
      Evaluate(AccelCostFunction<1>(shared_segment, sample), blocks.Pointers(1, true));
  const Evaluation local =
      Evaluate(AccelCostFunction<1>(local_segment, sample), blocks.Pointers(1, true));
  ExpectSame(stale_shared, local, kSameArithmeticTolerance);
}

TEST(ImuCostFunctions, ResidualsOnlyAndSkippedBlocksFollowTheCeresContract) {
  Blocks blocks = MakeBlocks(14);
  const ImuResidualSegment segment = TestSegment(1);
  const ImuResidualSample sample = MakeSample(0.3, 15, false);
  const AccelCostFunction<1> cost(segment, sample);
  const std::vector<double*> p = blocks.Pointers(1, true);
  const Evaluation full = Evaluate(cost, p);
  std::array<double, 3> residuals;
  ASSERT_TRUE(cost.Evaluate(p.data(), residuals.data(), nullptr));
  for (int r = 0; r < 3; ++r) EXPECT_EQ(residuals[r], full.residuals[r]);
  // Only the gravity Jacobian requested.
  std::vector<double> J_g(9, 0.0);
  std::array<double*, 6> jacobians = {nullptr, nullptr, nullptr, nullptr, nullptr, J_g.data()};
  ASSERT_TRUE(cost.Evaluate(p.data(), residuals.data(), jacobians.data()));
  EXPECT_LE(MaxRelativeDifference(J_g, full.jacobians[5]), kSameArithmeticTolerance);
}

}  // namespace
}  // namespace splinecal
