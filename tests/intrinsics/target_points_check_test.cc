// The test of the target's points against its file (intrinsics/target_points_check.h): with the
// true camera and poses held, a moved point's one-step displacement is its true one, and on a
// target that is its file the statistic follows chi-square; through CalibrateIntrinsics, a
// target whose points sit off its file (as a print and a detector put them) is named in a
// warning and an exact one is not.
#include "splinecal/intrinsics/target_points_check.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <string>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace {

// EuRoC's cam0 alone, 40 views of the file's AprilGrid (144 points).
testing::IntrinsicsScene Cam0Scene(double sigma_px) {
  testing::IntrinsicsScene scene = testing::EurocCam0Scene();
  scene.sigma_px = sigma_px;
  return scene;
}

// The check with the truth held: the scene's camera and each view's true pose, the corners
// observed from `truth` and matched to the points of `file`.
TargetPointsCheck CheckWithTheTruthHeld(const testing::IntrinsicsScene& scene,
                                        const CalibrationTarget& truth,
                                        const CalibrationTarget& file, int seed,
                                        std::vector<TargetView>* views) {
  testing::IntrinsicsScene observed = scene;
  observed.target = truth;
  std::vector<SE3d> T_c0_t;
  const std::vector<Observation> observations =
      testing::SimulateIntrinsicsViews(observed, seed, &T_c0_t);
  int64_t unknown = 0;
  *views = MakeTargetViews(observations, file, &unknown);
  EXPECT_EQ(unknown, 0);
  std::vector<TargetPointsCheckView> check_views;
  for (const TargetView& view : *views) {
    const int64_t v = (view.t_ns - 1'000'000'000) / 50'000'000;  // SimulateIntrinsicsViews' times
    check_views.push_back({scene.cameras[0], T_c0_t.at(v), &view, scene.sigma_px});
  }
  return CheckTargetPoints(check_views, kMinViewsPerFreePoint);
}

TEST(TargetPointsCheck, OneStepFindsAMovedPointWithTheTruthHeld) {
  const testing::IntrinsicsScene scene = Cam0Scene(1e-9);
  CalibrationTarget truth = scene.target;
  const Eigen::Vector3d moved(1.0e-3, -0.5e-3, 0.3e-3);
  const int64_t id = 50;
  truth.points.at(id) += moved;
  std::vector<TargetView> views;
  const TargetPointsCheck check = CheckWithTheTruthHeld(scene, truth, scene.target, 7, &views);
  ASSERT_GT(check.points, 100);
  EXPECT_EQ(check.dof, 3 * check.points - 7);
  // Every other point has no displacement: the largest is the moved one's, the RMS its share.
  // Linearisation: the pixel's second derivative over the first, ~1 mm / 1 m.
  EXPECT_NEAR(check.max_offset_m, moved.norm(), 0.01 * moved.norm());
  EXPECT_NEAR(check.rms_offset_m * std::sqrt(check.points), moved.norm(), 0.01 * moved.norm());
  EXPECT_GT(check.RatioToDof(), 1e6);  // noise-free
}

// sum_p T_p ~ chi-square(3 n) when nothing is fitted (the truth held): over 5 seeds, in the
// two-sided 95% interval.
TEST(TargetPointsCheck, ChiSquareOfAnExactTargetWithTheTruthHeld) {
  const testing::IntrinsicsScene scene = Cam0Scene(0.3);
  double sum = 0.0;
  int dof = 0;
  for (int seed = 1; seed <= 5; ++seed) {
    std::vector<TargetView> views;
    const TargetPointsCheck check =
        CheckWithTheTruthHeld(scene, scene.target, scene.target, seed, &views);
    sum += check.chi_square;
    dof += 3 * check.points;
  }
  std::printf("chi-square %.1f over %d\n", sum, dof);
  EXPECT_GT(sum, testing::ChiSquareQuantile(dof, -testing::kNormalQuantile975));
  EXPECT_LT(sum, testing::ChiSquareQuantile(dof, testing::kNormalQuantile975));
}

bool HasTargetPointsWarning(const IntrinsicsResult& result) {
  return std::any_of(result.warnings.begin(), result.warnings.end(), [](const std::string& w) {
    return w.find("--target-deformation points") != std::string::npos;
  });
}

IntrinsicsResult CalibrateFlat(const testing::IntrinsicsScene& scene,
                               const CalibrationTarget& truth, int seed) {
  testing::IntrinsicsScene observed = scene;
  observed.target = truth;
  IntrinsicsCameraSpec spec;
  spec.camera = scene.cameras[0];
  spec.initial_values = true;
  return CalibrateIntrinsics(testing::SimulateIntrinsicsViews(observed, 400 + seed), scene.target,
                             {spec}, IntrinsicsOptions());
}

// Through CalibrateIntrinsics, the poses and intrinsics fitted to the file's layout: a target
// whose points sit off it by N(0, 0.8 mm) in the plane and N(0, 0.4 mm) along the normal (EuRoC's
// target shows 0.93 mm RMS in the plane) is named, with its RMS displacement found to within a
// factor 2 of the truth's (the fitted poses and intrinsics take some of it); an exact target is
// not named, its statistic about 1 per degree of freedom (below it: the fitted parameters took
// their share of the noise).
TEST(TargetPointsCheck, CalibrateIntrinsicsNamesATargetOffItsFileAndNotAnExactOne) {
  const testing::IntrinsicsScene scene = Cam0Scene(0.3);
  std::mt19937 rng(5);
  std::normal_distribution<double> in_plane(0.0, 0.8e-3), normal(0.0, 0.4e-3);
  CalibrationTarget off = scene.target;
  double sum_squares = 0.0;
  for (auto& [id, p] : off.points) {
    const Eigen::Vector3d d(in_plane(rng), in_plane(rng), normal(rng));
    p += d;
    sum_squares += d.squaredNorm();
  }
  const double true_rms = std::sqrt(sum_squares / off.points.size());
  const IntrinsicsResult named = CalibrateFlat(scene, off, 1);
  const TargetPointsCheck& check = named.target_points_check;
  std::printf("off: ratio %.1f, RMS %.3f mm (truth %.3f mm)\n", check.RatioToDof(),
              1e3 * check.rms_offset_m, 1e3 * true_rms);
  EXPECT_GT(check.RatioToDof(), kTargetPointsWarnRatio);
  EXPECT_TRUE(HasTargetPointsWarning(named));
  EXPECT_GT(check.rms_offset_m, 0.5 * true_rms);
  EXPECT_LT(check.rms_offset_m, 2.0 * true_rms);
  for (int seed = 1; seed <= 2; ++seed) {
    const IntrinsicsResult exact = CalibrateFlat(scene, scene.target, seed);
    std::printf("exact, seed %d: ratio %.3f\n", seed, exact.target_points_check.RatioToDof());
    EXPECT_GT(exact.target_points_check.RatioToDof(), 0.5);
    EXPECT_LT(exact.target_points_check.RatioToDof(), 1.3);
    EXPECT_FALSE(HasTargetPointsWarning(exact));
  }
  // With every point free the check is not run.
  IntrinsicsCameraSpec spec;
  spec.camera = scene.cameras[0];
  spec.initial_values = true;
  IntrinsicsOptions options;
  options.target_deformation = TargetDeformationKind::kPoints;
  const IntrinsicsResult free = CalibrateIntrinsics(
      testing::SimulateIntrinsicsViews(scene, 401), scene.target, {spec}, options);
  EXPECT_EQ(free.target_points_check.points, 0);
}

}  // namespace
}  // namespace splinecal
