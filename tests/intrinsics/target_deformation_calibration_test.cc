// The target shape estimated with the intrinsics (IntrinsicsOptions::target_deformation) on
// simulated views of EuRoC's cam0 (pinhole-radtan, 40 views, 0.3 px noise, each solve started
// from the true intrinsics and a flat target):
// - a bowed target (the corners 2 mm above the centre) biases a flat model's focal length far
//   beyond its std, and the quadratic shape recovers both the bow and unbiased intrinsics;
// - a flat target: the shape found is consistent with zero and the intrinsics' stds barely grow.
// Measured with these seeds (docs/intrinsics.md, "Is the target flat?"): flat model fu off by
// 9.6, 4.6, 7.5 std on the bowed target, the quadratic shape's |z| at most 0.9.
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <cmath>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "testing/chi_square.h"

namespace splinecal {
namespace {

testing::IntrinsicsScene Scene(double corner_height_m) {
  testing::IntrinsicsScene scene;
  scene.cameras = {testing::EurocCam0()};
  scene.T_cn_c0 = {SE3d()};
  scene.views = 40;
  if (corner_height_m != 0.0) {
    // h = c (s^2 + t^2): the corners (s, t = +-1) 2 c above the centre.
    scene.shape_kind = TargetDeformationKind::kQuadratic;
    scene.shape[0] = scene.shape[2] = 0.5 * corner_height_m;
  }
  return scene;
}

IntrinsicsResult Calibrate(const testing::IntrinsicsScene& scene, int seed,
                           TargetDeformationKind kind) {
  IntrinsicsCameraSpec spec;
  spec.camera = scene.cameras[0];
  spec.initial_values = true;
  IntrinsicsOptions options;
  options.target_deformation = kind;
  return CalibrateIntrinsics(
      testing::SimulateIntrinsicsViews(scene, 100 + seed), scene.target, {spec}, options);
}

// (estimate - truth) / std of every active intrinsic.
Eigen::VectorXd IntrinsicsZ(const IntrinsicsCameraResult& camera, const Camera& truth) {
  Eigen::VectorXd z(camera.active.size());
  for (size_t j = 0; j < camera.active.size(); ++j) {
    const int i = camera.active[j];
    z(j) = (camera.camera.intrinsics()(i) - truth.intrinsics()(i)) / camera.intrinsics_std(i);
  }
  return z;
}

TEST(TargetDeformationCalibration, RecoversABowedTargetAndUnbiasedIntrinsics) {
  const testing::IntrinsicsScene scene = Scene(2e-3);
  for (int seed = 1; seed <= 3; ++seed) {
    SCOPED_TRACE(seed);
    const IntrinsicsResult flat = Calibrate(scene, seed, TargetDeformationKind::kNone);
    // The bow is there: the flat model's fu is biased (measured 4.6 to 9.6 std).
    EXPECT_GT(std::abs(IntrinsicsZ(flat.cameras[0], scene.cameras[0])(0)), 3.0);
    const IntrinsicsResult shaped = Calibrate(scene, seed, TargetDeformationKind::kQuadratic);
    // Each estimate within 3 of its stds (a 0.3% chance per entry for an honest std; measured
    // at most 0.9).
    EXPECT_LE(IntrinsicsZ(shaped.cameras[0], scene.cameras[0]).cwiseAbs().maxCoeff(), 3.0);
    const TargetDeformationResult& d = shaped.target_deformation;
    ASSERT_EQ(d.coefficients.size(), 3);
    ASSERT_EQ(d.covariance.rows(), 3);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(d.coefficients(k) - scene.shape[k]), 3.0 * std::sqrt(d.covariance(k, k)))
          << "coefficient " << k;
    }
    // The corner (-a, -a) 2 mm above the centre in the reported heights (relative to the
    // least-squares plane, so their difference is the surface's own: c_0 + c_1 + c_2).
    ASSERT_EQ(d.heights_m.size(), 5);
    const Eigen::Vector3d v(1.0, 1.0, 1.0);
    EXPECT_NEAR(d.heights_m(1) - d.heights_m(0), 2e-3, 3.0 * std::sqrt(v.dot(d.covariance * v)));
  }
}

TEST(TargetDeformationCalibration, AFlatTargetStaysFlatAndTheStdsBarelyGrow) {
  const testing::IntrinsicsScene scene = Scene(0.0);
  constexpr int kSeeds = 5;
  double nees = 0.0;
  for (int seed = 1; seed <= kSeeds; ++seed) {
    SCOPED_TRACE(seed);
    const IntrinsicsResult flat = Calibrate(scene, seed, TargetDeformationKind::kNone);
    const IntrinsicsResult shaped = Calibrate(scene, seed, TargetDeformationKind::kQuadratic);
    const TargetDeformationResult& d = shaped.target_deformation;
    ASSERT_EQ(d.covariance.rows(), 3);
    nees += d.coefficients.dot(d.covariance.ldlt().solve(d.coefficients));
    // Three more unknowns against ~1000 corners: each intrinsic's std grows by at most 30%
    // (measured: fu by 2-19%, the others by less).
    for (int i : flat.cameras[0].active) {
      EXPECT_LE(shaped.cameras[0].intrinsics_std(i), 1.3 * flat.cameras[0].intrinsics_std(i))
          << "intrinsic " << i;
    }
  }
  // Zero shape: the NEES of the coefficients is chi-square with 3 kSeeds dof (measured 10.3).
  const int dof = 3 * kSeeds;
  EXPECT_GT(nees, testing::ChiSquareQuantile(dof, -testing::kNormalQuantile975));
  EXPECT_LT(nees, testing::ChiSquareQuantile(dof, testing::kNormalQuantile975));
}

}  // namespace
}  // namespace splinecal
