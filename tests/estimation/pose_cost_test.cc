#include "splinecal/estimation/detail/pose_cost.h"

#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <array>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/autodiff_costs.h"
#include "testing/trajectory_models.h"

namespace splinecal {
namespace {

// Analytic against autodiff (issue: 1e-9), relative to max(1, |entry|); both are exact.
constexpr double kAutoDiffTolerance = 1e-9;
// ceres::GradientChecker's numeric Jacobians: 1e-6 relative for the pose blocks; its time-offset
// column is ~3e-5 off (its step, 1e-6 of the offset, against a second time derivative of the
// residual ~1e5 times its first), so that block is held to 1e-4. The exact comparison is
// AnalyticMatchesAutoDiffAtLargeResiduals (1e-9).
constexpr double kGradientCheckerPrecision = 1e-4;
// A measurement generated from the model itself gives a zero residual up to rounding.
constexpr double kZeroResidualTolerance = 1e-9;

constexpr double kDtS = 0.1;

struct PoseBlocks {
  std::vector<std::array<double, 7>> control;
  std::array<double, 1> time_offset = {0.0};
  std::array<double, 7> T_m_s;
  std::vector<double*> Pointers() {
    return {control[0].data(),
            control[1].data(),
            control[2].data(),
            control[3].data(),
            time_offset.data(),
            T_m_s.data()};
  }
};

PoseBlocks MakeBlocks(uint64_t seed, double time_offset) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> normal(0.0, 1.0);
  PoseBlocks b;
  SE3d T = SE3d::Exp((Vector6d() << 0.5, 1.0, -0.3, 0.2, 0.4, -2.5).finished());
  for (int i = 0; i < 4; ++i) {
    Vector6d xi;
    for (int k = 0; k < 3; ++k) xi[k] = 0.8 * normal(rng);
    for (int k = 3; k < 6; ++k) xi[k] = 0.3 * normal(rng);
    T = T * SE3d::Exp(xi);
    b.control.emplace_back();
    PoseToBlock(T, b.control.back().data());
  }
  b.time_offset[0] = time_offset;
  // A 10 cm / ~17 deg extrinsic.
  PoseToBlock(SE3d::Exp((Vector6d() << 0.06, -0.05, 0.06, 0.2, -0.1, 0.15).finished()),
              b.T_m_s.data());
  return b;
}

PoseResidualData MakeData(double t_s, uint64_t seed, double residual_size) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> normal(0.0, 1.0);
  PoseResidualData data;
  data.segment_index = 7;
  data.dt_s = kDtS;
  data.t_s = t_s;
  Vector6d xi;
  for (int k = 0; k < 6; ++k) xi[k] = normal(rng);
  data.T_w_m = SE3d::Exp(residual_size * xi) *
               SE3d::Exp((Vector6d() << 1.0, 2.0, 0.5, 0.1, 0.3, -2.4).finished());
  data.sigma_m = 0.01;
  data.sigma_rad = 0.02;
  return data;
}

struct Evaluation {
  std::array<double, 6> residuals;
  std::vector<std::vector<double>> jacobians;
};

Evaluation Evaluate(const ceres::CostFunction& cost, PoseBlocks* blocks) {
  Evaluation e;
  const std::vector<int> sizes = {7, 7, 7, 7, 1, 7};
  std::vector<double*> pointers;
  for (int size : sizes) {
    e.jacobians.emplace_back(6 * size, 0.0);
    pointers.push_back(e.jacobians.back().data());
  }
  EXPECT_TRUE(cost.Evaluate(blocks->Pointers().data(), e.residuals.data(), pointers.data()));
  return e;
}

double MaxRelativeDifference(const double* a, const double* b, size_t n) {
  double worst = 0.0;
  for (size_t k = 0; k < n; ++k) {
    worst = std::max(worst, std::abs(a[k] - b[k]) / std::max(1.0, std::abs(b[k])));
  }
  return worst;
}

// Pose times inside the segment, at its ends, and outside it (a time offset that moved the pose
// into a neighbouring segment: the segment polynomial is evaluated at u outside [0, 1]).
const double kTimes[] = {0.705, 0.7, 0.8, 0.77, 0.64, 0.86};

// Every test runs on both trajectory models (PoseResidualData::model).
class PoseCostFunction : public ::testing::TestWithParam<TrajectoryModel> {};

TEST_P(PoseCostFunction, AnalyticMatchesAutoDiffAtLargeResiduals) {
  for (double t_s : kTimes) {
    for (double residual_size : {0.0, 0.1, 1.0}) {
      for (double offset : {0.004, -0.08}) {
        PoseBlocks blocks = MakeBlocks(3, offset);
        PoseResidualData data = MakeData(t_s - offset, 4, residual_size);
        data.model = GetParam();
        const splinecal::PoseCostFunction analytic(data);
        std::unique_ptr<ceres::CostFunction> autodiff(testing::NewAutoDiffPoseCost(data));
        const Evaluation a = Evaluate(analytic, &blocks);
        const Evaluation b = Evaluate(*autodiff, &blocks);
        EXPECT_LE(MaxRelativeDifference(a.residuals.data(), b.residuals.data(), 6),
                  kAutoDiffTolerance);
        for (int i = 0; i < 6; ++i) {
          EXPECT_LE(MaxRelativeDifference(
                        a.jacobians[i].data(), b.jacobians[i].data(), a.jacobians[i].size()),
                    kAutoDiffTolerance)
              << "t = " << t_s << ", block " << i;
        }
      }
    }
  }
}

TEST_P(PoseCostFunction, PassesCeresGradientChecker) {
  const SE3Manifold se3;
  const std::vector<const ceres::Manifold*> manifolds = {&se3, &se3, &se3, &se3, nullptr, &se3};
  for (double t_s : kTimes) {
    // At u = 1 (t = 0.8) the pose is P_2 Exp(Omega_3 / 6): its Jacobian with respect to P_0 is
    // zero up to rounding, which GradientChecker's per-entry relative error cannot pass.
    if (t_s == 0.8) continue;
    // Ceres' numeric step is relative to the parameter: an offset of -0.08 s gives a step of
    // 8e-8 s, large enough against rounding of residuals ~100 (a 3 ms offset would not be).
    constexpr double kOffset = -0.08;
    PoseBlocks blocks = MakeBlocks(5, kOffset);
    // Stamped t_s - offset, so that the spline is evaluated at t_s (u in [-0.6, 1.6]; further
    // out, the extrapolated rotation can approach pi from the measurement, where Log jumps).
    PoseResidualData data = MakeData(t_s - kOffset, 6, 0.5);
    data.model = GetParam();
    const splinecal::PoseCostFunction cost(data);
    ceres::GradientChecker checker(&cost, &manifolds, ceres::NumericDiffOptions());
    ceres::GradientChecker::ProbeResults results;
    EXPECT_TRUE(checker.Probe(blocks.Pointers().data(), kGradientCheckerPrecision, &results))
        << results.error_log;
  }
}

TEST_P(PoseCostFunction, IsZeroForAPoseTakenFromTheModel) {
  PoseBlocks blocks = MakeBlocks(7, 0.005);
  PoseResidualData data = MakeData(0.73, 8, 0.0);
  data.model = GetParam();
  // The spline segment at t_s + offset, through the extrinsic.
  const SegmentKnotData<double> knots(PoseFromBlock(blocks.control[0].data()),
                                      PoseFromBlock(blocks.control[1].data()),
                                      PoseFromBlock(blocks.control[2].data()),
                                      PoseFromBlock(blocks.control[3].data()));
  const double u = (data.t_s + blocks.time_offset[0]) / kDtS - data.segment_index;
  SE3d T_w_s;
  EvaluateSegment(data.model, knots.knots(), MakeSegment(data.segment_index, u, kDtS), &T_w_s);
  data.T_w_m = T_w_s * PoseFromBlock(blocks.T_m_s.data()).inverse();
  const Evaluation e = Evaluate(splinecal::PoseCostFunction(data), &blocks);
  for (double r : e.residuals) EXPECT_NEAR(r, 0.0, kZeroResidualTolerance);
}

INSTANTIATE_TEST_SUITE_P(Models,
                         PoseCostFunction,
                         testing::BothTrajectoryModels(),
                         testing::TrajectoryModelTestName);

}  // namespace
}  // namespace splinecal
