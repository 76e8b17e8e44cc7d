// intrinsics/compare_models.h: on a simulated double-sphere fisheye every compared model fits the
// very corners the main calibration used, and the true model has the smallest sum of squares.
#include "splinecal/intrinsics/compare_models.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "intrinsics/intrinsics_models.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

TEST(CompareModels, TheTrueModelFitsBestOnTheSameCorners) {
  const testing::ModelCase ds = testing::AllModelCases()[7];
  ASSERT_EQ(ds.name, "ds-none");
  const Camera& truth = ds.scene.cameras[0];
  const IntrinsicsCameraSpec spec = testing::SpecOf(truth);
  IntrinsicsOptions options;
  options.solver.max_iterations = 100;
  const IntrinsicsResult result = CalibrateIntrinsics(
      testing::SimulateIntrinsicsViews(ds.scene, 3), ds.scene.target, {spec}, options);
  const std::vector<ModelFit> fits = CompareModels(result, ds.scene.target, {spec}, options);
  ASSERT_EQ(fits.size(), 3u);
  EXPECT_EQ(fits[0].model, "pinhole-radtan");
  EXPECT_EQ(fits[1].model, "pinhole-equi");
  EXPECT_EQ(fits[2].model, "ds-none");
  const ModelFit& own = fits[2];
  ASSERT_TRUE(own.failure.empty()) << own.failure;
  // The same corners as the main calibration, every one of them (no outlier pass).
  EXPECT_EQ(own.cameras[0].corners_used, result.cameras[0].corners_used);
  // The true model at the noise level: RMS of the 2-d error with 0.3 px per component is
  // 0.3 sqrt(2) = 0.42 px, a little less for the parameters' share of the redundancy (5%).
  EXPECT_NEAR(own.cameras[0].reprojection_rms_px, 0.3 * std::sqrt(2.0), 0.05);
  for (const ModelFit& fit : fits) {
    SCOPED_TRACE(fit.model);
    if (!fit.failure.empty()) continue;  // a model that cannot start on a fisheye says why
    EXPECT_EQ(fit.cameras[0].corners_used, result.cameras[0].corners_used);
    // Up to the solver's tolerance, no model fits the true model's noise better than it: the
    // models nest only partly, so a wrong one can at best match it.
    EXPECT_GE(fit.sum_of_squares_px2[0], own.sum_of_squares_px2[0] * (1.0 - 1e-3));
  }
  // radtan's polynomial cannot describe a 512 px double-sphere fisheye's border: it fails to
  // start or leaves a sum of squares well above the noise (measured: many times ds-none's).
  if (fits[0].failure.empty()) {
    EXPECT_GT(fits[0].sum_of_squares_px2[0], 1.5 * own.sum_of_squares_px2[0]);
  }
  const std::string text = ModelComparisonText(fits);
  EXPECT_THAT(text, HasSubstr("cam0    ds-none"));
  EXPECT_THAT(text, HasSubstr("xi -0.1"));
}

}  // namespace
}  // namespace splinecal
