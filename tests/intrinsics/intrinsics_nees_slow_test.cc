// Are the intrinsics' reported covariances honest? For every camera model (wide-angle
// included), 20 simulated seeds, each solve started from the truth: the normalised estimation
// error squared NEES = e^T C^-1 e of the active intrinsics, summed over the seeds, is chi-square
// with 20 k degrees of freedom when C is right; the test asks it to lie in the central 95% band.
// omni-radtan is not identifiable enough for that (the test says why).
#include <gtest/gtest.h>

#include <Eigen/Cholesky>
#include <string>

#include "intrinsics/intrinsics_models.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "testing/chi_square.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

constexpr int kSeeds = 20;

TEST(IntrinsicsNees, EveryModelInItsNinetyFivePercentBand) {
  for (const testing::ModelCase& c : testing::AllModelCases()) {
    SCOPED_TRACE(c.name);
    double nees = 0.0;
    int dof = 0;
    for (int seed = 1; seed <= kSeeds; ++seed) {
      IntrinsicsCameraSpec spec;
      ASSERT_TRUE(ParseCameraModelName(c.name, &spec.camera.projection, &spec.camera.distortion));
      // Started from the truth, not the sweep: the sweep's grid of PnP solves
      // (initial_intrinsics.cc) was 80% of this test's CPU (44.0 CPU-s against 8.1), and from
      // either start the seeds' solves reach the same minima: each model's NEES the same to the
      // printed 0.1 (pinhole-none 76.2 and 76.1, the others identical; docs/reliability.md,
      // "Test time before / after"). The sweep's own start is tested on every model by
      // CalibrateIntrinsics.EveryModelFromTheSweepWithinThreeStd.
      const Camera& true_camera = c.scene.cameras[0];
      ASSERT_EQ(spec.camera.projection, true_camera.projection);
      ASSERT_EQ(spec.camera.distortion, true_camera.distortion);
      spec.camera = true_camera;
      spec.initial_values = true;
      IntrinsicsOptions options;
      // Never stopped by the count; the default tolerances (function and parameter 1e-10
      // relative) stop where a further step moves no printed NEES: each model's sum was the same
      // to 0.1 with 1e-16 / 1e-14 (docs/reliability.md, "Test time before / after").
      options.solver.max_iterations = 1000;
      const IntrinsicsResult result = CalibrateIntrinsics(
          testing::SimulateIntrinsicsViews(c.scene, 100 + seed), c.scene.target, {spec}, options);
      const IntrinsicsCameraResult& camera = result.cameras[0];
      if (c.name == "omni-radtan") {
        // Mei's xi and radtan's k1 both bend rays radially: even on this 512 x 512 fisheye the
        // estimates trade along a curved valley (fu's std 10-130 px over the seeds, xi from
        // 0.74 to 1.39 for a truth of 0.95) where no linearised covariance holds: measured
        // NEES 41883 over 180 dof (docs/intrinsics.md, "Choosing a model"). Left out of the
        // band; its fit must still explain the pixels (RMS of a 2-D error: sqrt(2) sigma).
        EXPECT_NEAR(camera.reprojection_rms_px, std::sqrt(2.0) * c.scene.sigma_px,
                    0.1 * std::sqrt(2.0) * c.scene.sigma_px);
        continue;
      }
      const IntrinsicsVector estimate = camera.camera.intrinsics();
      const IntrinsicsVector truth = c.scene.cameras[0].intrinsics();
      Eigen::VectorXd e(camera.active.size());
      for (size_t j = 0; j < camera.active.size(); ++j) {
        e(j) = estimate(camera.active[j]) - truth(camera.active[j]);
      }
      ASSERT_EQ(camera.intrinsics_covariance.rows(), e.size());
      nees += e.dot(camera.intrinsics_covariance.ldlt().solve(e));
      dof += static_cast<int>(e.size());
    }
    if (dof == 0) continue;  // omni-radtan (above)
    const double low = testing::ChiSquareQuantile(dof, -testing::kNormalQuantile975);
    const double high = testing::ChiSquareQuantile(dof, testing::kNormalQuantile975);
    std::printf("%-15s NEES %.1f over %d dof, 95%% band [%.1f, %.1f]\n", c.name.c_str(), nees, dof,
                low, high);
    EXPECT_GT(nees, low);
    EXPECT_LT(nees, high);
  }
}

}  // namespace
}  // namespace splinecal
