// Every camera model through splinecal intrinsics on a few views: the sanitizer build's run of
// each model's projection inside the intrinsics solve, its covariance and its report fields
// (the accuracy of every model, on 40 views, is CalibrateIntrinsics.EveryModelFromTheSweep-
// WithinThreeStd, which only the Release build runs: tests/sanitize_skip.cmake).
#include <gtest/gtest.h>

#include <cmath>

#include "intrinsics/intrinsics_models.h"
#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"

namespace splinecal {
namespace {

// 6 views instead of the sweep's 40: enough corners for every model's parameters to be
// determined (4 to 10 intrinsics and 6 poses against hundreds of corners), few enough that the
// 8 solves stay cheap under the sanitizers (1.0 CPU-s for the test in Release).
constexpr int kViews = 6;

TEST(CalibrateIntrinsicsModels, EveryModelFitsAFewViewsAtThePixelNoise) {
  for (testing::ModelCase c : testing::AllModelCases()) {
    SCOPED_TRACE(c.name);
    c.scene.views = kViews;
    // The truth's model and image size; its values are no start (initial_values is false: the
    // sweep finds the start, as in the 40-view test).
    IntrinsicsCameraSpec spec;
    spec.camera = c.scene.cameras[0];
    IntrinsicsOptions options;
    options.solver.max_iterations = 100;
    const IntrinsicsResult result = CalibrateIntrinsics(
        testing::SimulateIntrinsicsViews(c.scene, 21), c.scene.target, {spec}, options);
    ASSERT_EQ(result.cameras.size(), 1u);
    const IntrinsicsCameraResult& camera = result.cameras[0];
    EXPECT_EQ(camera.views_used, kViews);
    EXPECT_EQ(camera.camera.model_name(), c.name);
    // Converged to the noise: the RMS of a 2-D error of sigma per axis is sqrt(2) sigma; 15%
    // covers the residuals' shrinking by the fitted parameters (6 x 6 pose and up to 10
    // intrinsic parameters against over 600 residuals: the RMS lower by under 4%) and one
    // seed's scatter.
    EXPECT_NEAR(camera.reprojection_rms_px, std::sqrt(2.0) * c.scene.sigma_px,
                0.15 * std::sqrt(2.0) * c.scene.sigma_px);
    // A covariance for every active intrinsic: finite, positive stds.
    for (int i : camera.active) {
      EXPECT_TRUE(std::isfinite(camera.intrinsics_std(i))) << i;
      EXPECT_GT(camera.intrinsics_std(i), 0.0) << i;
    }
  }
}

}  // namespace
}  // namespace splinecal
