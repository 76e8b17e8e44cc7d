#include "splinecal/estimation/pose_fit.h"

#include <ceres/autodiff_cost_function.h>
#include <ceres/gradient_checker.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/spline/trajectory_model.h"
#include "testing/trajectory_models.h"

namespace splinecal {
namespace {

// Fitting a spline's own samples with the same knots: the optimum is the spline itself, reached
// to the solver's tolerances (parameter tolerance 1e-12 relative).
constexpr double kSelfFitTolerance = 1e-8;
// The issue: a smooth trajectory is recovered "to well under a millimetre". vio_course with
// dt = 0.05 s: the cubic B-spline's approximation error is ~dt^4 |p''''| / 384 ~ 2e-6 m for
// z = sin(pi t) (|p''''| = pi^4); we allow 2e-5 m (50x below a millimetre).
constexpr double kSmoothFitPositionTolerance = 2e-5;
constexpr double kSmoothFitRotationToleranceDeg = 1e-3;

// Ceres' central differences (Ridders off) have error ~1e-9 relative at these magnitudes.
constexpr double kJacobianTolerance = 1e-7;

std::vector<StampedPose> SampleSpline(const SE3Splined& spline, int64_t step_ns) {
  std::vector<StampedPose> poses;
  for (int64_t t = spline.start_time_ns(); t <= spline.end_time_ns(); t += step_ns) {
    const SE3d T_w_s = spline.PoseNs(t);
    StampedPose pose;
    pose.t_ns = t;
    pose.p = T_w_s.translation();
    pose.q = T_w_s.so3().quaternion();
    poses.push_back(pose);
  }
  return poses;
}

SE3Splined RandomSmoothSpline(int n,
                              int64_t t0_ns,
                              int64_t dt_ns,
                              uint64_t seed,
                              TrajectoryModel model = TrajectoryModel::kSE3) {
  std::mt19937 rng(static_cast<unsigned>(seed));
  std::normal_distribution<double> normal(0.0, 1.0);
  std::vector<SE3d> control(n);
  Vector6d xi = Vector6d::Zero();
  SE3d T;
  for (int i = 0; i < n; ++i) {
    for (int k = 0; k < 6; ++k) xi[k] = 0.8 * xi[k] + (k < 3 ? 0.05 : 0.03) * normal(rng);
    T = T * SE3d::Exp(xi);
    control[i] = T;
  }
  return SE3Splined(control, t0_ns, dt_ns, model);
}

TEST(KnotLayoutCovering, FirstValidKnotAtStartAndEndCovered) {
  const KnotLayout layout = KnotLayoutCovering(1'000, 1'000 + 20'000, 5'000);
  EXPECT_EQ(layout.t0_ns, 1'000 - 5'000);
  EXPECT_EQ(layout.dt_ns, 5'000);
  EXPECT_EQ(layout.num_control_poses, 4 + 3);  // t_1 = 1000, t_{n-2} = 21000
  const KnotLayout partial = KnotLayoutCovering(0, 20'001, 5'000);
  EXPECT_EQ(partial.num_control_poses, 5 + 3);
  EXPECT_GE(partial.t0_ns + (partial.num_control_poses - 2) * partial.dt_ns, 20'001);
  EXPECT_THROW(KnotLayoutCovering(0, 10, 0), Error);
  EXPECT_THROW(KnotLayoutCovering(10, 0, 5), Error);
}

// Both trajectory models (PoseFitOptions::trajectory).
class SegmentPoseCost : public ::testing::TestWithParam<TrajectoryModel> {};

TEST_P(SegmentPoseCost, AnalyticJacobiansMatchNumericThroughTheManifold) {
  // Residuals far from zero (measured poses up to ~0.5 rad and 0.5 m off), so that Jr^-1(r)
  // matters.
  const SE3Splined spline = RandomSmoothSpline(4, 0, 100'000'000, 3, GetParam());
  std::mt19937 rng(4);
  std::normal_distribution<double> normal(0.0, 0.3);
  std::vector<double> u = {0.0, 0.2, 0.55, 0.9, 1.0};
  std::vector<SE3d> measured;
  for (double uj : u) {
    Vector6d offset;
    for (int k = 0; k < 6; ++k) offset[k] = normal(rng);
    measured.push_back(spline.Pose(0.1 * (1.0 + uj)) * SE3d::Exp(offset));
  }
  std::unique_ptr<ceres::CostFunction> cost(
      internal::NewSegmentPoseCost(u, measured, 0.1, 2.0, GetParam()));
  std::vector<std::array<double, 7>> blocks(4);
  for (int k = 0; k < 4; ++k) PoseToBlock(spline.control_pose(k), blocks[k].data());
  const double* parameters[4] = {
      blocks[0].data(), blocks[1].data(), blocks[2].data(), blocks[3].data()};
  SE3Manifold manifold;
  std::vector<const ceres::Manifold*> manifolds(4, &manifold);
  ceres::NumericDiffOptions numeric_options;
  ceres::GradientChecker checker(cost.get(), &manifolds, numeric_options);
  ceres::GradientChecker::ProbeResults results;
  checker.Probe(parameters, 1e-7, &results);
  // Compared in the tangent space of each block (what the solver uses). Absolute error: entries
  // that are exactly zero (block 0 at u = 1) differ by rounding, which a relative test rejects.
  ASSERT_EQ(results.local_jacobians.size(), 4u);
  for (int k = 0; k < 4; ++k) {
    const double scale = results.local_numeric_jacobians[k].cwiseAbs().maxCoeff();
    const double error =
        (results.local_jacobians[k] - results.local_numeric_jacobians[k]).cwiseAbs().maxCoeff();
    EXPECT_LT(error, kJacobianTolerance * std::max(1.0, scale)) << "block " << k << "\n"
                                                                << results.error_log;
  }
}

// The smoothness prior's analytic Jacobians against Ceres' automatic differentiation of the
// same residual through PoseFromBlock, at unit quaternions (the blocks the manifold keeps), on
// control poses perturbed by ~0.3 rad and 0.3 m (large Omega: Jr^-1 and Jl^-1 far from I).
struct SmoothnessPriorByAutodiff {
  template <typename T>
  bool operator()(const T* a, const T* b, const T* c, T* residual) const {
    const SE3<T> T_a = PoseFromBlock(a);
    const SE3<T> T_b = PoseFromBlock(b);
    const SE3<T> T_c = PoseFromBlock(c);
    const Vector6<T> r = T(weight) * ((T_a.inverse() * T_b).Log() - (T_b.inverse() * T_c).Log());
    for (int k = 0; k < 6; ++k) residual[k] = r[k];
    return true;
  }
  double weight = 0.3;
};

TEST(SmoothnessPriorCost, AnalyticJacobiansMatchAutomaticDifferentiation) {
  const SE3Splined spline = RandomSmoothSpline(4, 0, 100'000'000, 5);
  std::mt19937 rng(6);
  std::normal_distribution<double> normal(0.0, 0.3);
  std::vector<std::array<double, 7>> blocks(3);
  for (int k = 0; k < 3; ++k) {
    Vector6d offset;
    for (int a = 0; a < 6; ++a) offset[a] = normal(rng);
    PoseToBlock(spline.control_pose(k) * SE3d::Exp(offset), blocks[k].data());
  }
  const double* parameters[3] = {blocks[0].data(), blocks[1].data(), blocks[2].data()};
  std::unique_ptr<ceres::CostFunction> analytic(internal::NewSmoothnessPriorCost(0.3));
  ceres::AutoDiffCostFunction<SmoothnessPriorByAutodiff, 6, 7, 7, 7> automatic(
      new SmoothnessPriorByAutodiff);
  double r_analytic[6];
  double r_automatic[6];
  std::array<std::array<double, 42>, 3> J_analytic;
  std::array<std::array<double, 42>, 3> J_automatic;
  double* ja[3] = {J_analytic[0].data(), J_analytic[1].data(), J_analytic[2].data()};
  double* jb[3] = {J_automatic[0].data(), J_automatic[1].data(), J_automatic[2].data()};
  ASSERT_TRUE(analytic->Evaluate(parameters, r_analytic, ja));
  ASSERT_TRUE(automatic.Evaluate(parameters, r_automatic, jb));
  for (int k = 0; k < 6; ++k) EXPECT_NEAR(r_analytic[k], r_automatic[k], 1e-14);
  for (int b = 0; b < 3; ++b) {
    for (int e = 0; e < 42; ++e) {
      // Both exact: equal to rounding of terms of order weight * |Omega|.
      EXPECT_NEAR(J_analytic[b][e], J_automatic[b][e], 1e-12) << "block " << b << " entry " << e;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Models,
                         SegmentPoseCost,
                         testing::BothTrajectoryModels(),
                         testing::TrajectoryModelTestName);

class FitControlPosesOfModel : public ::testing::TestWithParam<TrajectoryModel> {};

TEST_P(FitControlPosesOfModel, RecoversTheSplineFromItsOwnSamples) {
  const SE3Splined truth = RandomSmoothSpline(24, 1'000'000'000, 50'000'000, 7, GetParam());
  const std::vector<StampedPose> poses = SampleSpline(truth, 7'000'000);
  KnotLayout layout;
  layout.t0_ns = truth.t0_ns();
  layout.dt_ns = truth.dt_ns();
  layout.num_control_poses = truth.num_control_poses();
  PoseFitOptions options;
  options.smoothness_weight = 0.0;
  options.trajectory = GetParam();
  const PoseFitResult fit = FitControlPoses(poses, layout, options);
  EXPECT_EQ(fit.MakeSpline().model(), GetParam());
  EXPECT_TRUE(fit.converged) << fit.solver_report;
  EXPECT_EQ(fit.num_poses, static_cast<int64_t>(poses.size()));
  EXPECT_LT(fit.max_position_error_m, kSelfFitTolerance);
  EXPECT_LT(fit.max_rotation_error_deg, kSelfFitTolerance);
  for (int i = 0; i < truth.num_control_poses(); ++i) {
    const Vector6d d = (truth.control_pose(i).inverse() * fit.control_poses[i]).Log();
    EXPECT_LT(d.norm(), 1e-6) << "control pose " << i;
  }
}

INSTANTIATE_TEST_SUITE_P(Models,
                         FitControlPosesOfModel,
                         testing::BothTrajectoryModels(),
                         testing::TrajectoryModelTestName);

TEST(FitControlPoses, RecoversVioCourseWellUnderAMillimetre) {
  const AnalyticTrajectory course = VioCourseTrajectory();
  const int64_t start_ns = 50'000'000;
  const int64_t end_ns = start_ns + 20'000'000'000;
  const std::vector<StampedPose> poses = course.Sample(start_ns, end_ns, 5'000'000);
  const PoseFitResult fit =
      FitControlPoses(poses, KnotLayoutCovering(start_ns, end_ns, 50'000'000));
  std::printf(
      "vio_course fit: position RMS %.3g m (max %.3g), rotation RMS %.3g deg (max %.3g), "
      "%d iterations\n",
      fit.position_rms_m,
      fit.max_position_error_m,
      fit.rotation_rms_deg,
      fit.max_rotation_error_deg,
      fit.iterations);
  EXPECT_EQ(fit.num_poses, static_cast<int64_t>(poses.size()));
  EXPECT_LT(fit.max_position_error_m, kSmoothFitPositionTolerance);
  EXPECT_LT(fit.max_rotation_error_deg, kSmoothFitRotationToleranceDeg);
  // Between the fitted samples too (the spline does not wiggle): every 1.3 ms.
  const SE3Splined spline = fit.MakeSpline();
  for (int64_t t = start_ns; t <= end_ns; t += 1'300'000) {
    const SE3d T_true = course.Pose(static_cast<double>(t - start_ns) * 1e-9);
    ASSERT_LT((spline.PoseNs(t).translation() - T_true.translation()).norm(),
              kSmoothFitPositionTolerance)
        << "t = " << t;
  }
}

TEST(FitControlPoses, SparsePosesStayDeterminedWithTheSmoothnessPrior) {
  // One pose per knot interval (20 Hz, dt = 50 ms): 3 control poses more than the data fixes.
  // The prior decides them; the spline still follows the course between the poses.
  const AnalyticTrajectory course = VioCourseTrajectory();
  const int64_t end_ns = 10'000'000'000;
  const std::vector<StampedPose> poses = course.Sample(0, end_ns, 50'000'000);
  const PoseFitResult fit = FitControlPoses(poses, KnotLayoutCovering(0, end_ns, 50'000'000));
  EXPECT_LT(fit.max_position_error_m, 1e-4);
  const SE3Splined spline = fit.MakeSpline();
  double worst = 0.0;
  for (int64_t t = 0; t <= end_ns; t += 3'000'000) {
    worst = std::max(
        worst,
        (spline.PoseNs(t).translation() - course.Pose(static_cast<double>(t) * 1e-9).translation())
            .norm());
  }
  EXPECT_LT(worst, 1e-3);
}

TEST(FitControlPoses, RejectsBadInput) {
  const std::vector<StampedPose> poses = VioCourseTrajectory().Sample(0, 1'000'000'000, 10'000'000);
  std::vector<StampedPose> shuffled = poses;
  std::swap(shuffled[3], shuffled[4]);
  EXPECT_THROW(FitControlPoses(shuffled, KnotLayoutCovering(0, 1'000'000'000, 50'000'000)), Error);
  EXPECT_THROW(FitControlPoses({poses[0]}, KnotLayoutCovering(0, 1'000'000'000, 50'000'000)),
               Error);
  KnotLayout too_small;
  too_small.dt_ns = 50'000'000;
  too_small.num_control_poses = 3;
  EXPECT_THROW(FitControlPoses(poses, too_small), Error);
  // All poses outside the spline's range.
  EXPECT_THROW(FitControlPoses(poses, KnotLayoutCovering(5'000'000'000, 6'000'000'000, 50'000'000)),
               Error);
}

}  // namespace
}  // namespace splinecal
