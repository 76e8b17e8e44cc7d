// The user's path through a fisheye, end to end: a simulated camera-IMU recording rendered
// through a 512 x 512 double-sphere lens of about 190 degrees (like TUM-VI's cameras) into image
// files, `splinecal detect` on them, `splinecal intrinsics` (ds-none, from nothing but the image
// size) on its corners, and `splinecal calibrate` with that camchain and its covariance. No truth
// enters the chain; the rig must come back.
#include <gtest/gtest.h>

#include <cmath>

#include "detect/rendered_recording.h"
#include "splinecal/io/camchain_yaml.h"
#include "testing/run_tool.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

TEST(FisheyeChain, ImagesThroughAFisheyeGiveItsIntrinsicsAndTheRigBack) {
  testing::ScenarioOptions o = testing::RenderedScenarioOptions(8.0);
  o.camera = testing::TumViLikeFisheye();
  // EuRoC's grid of 8.8 cm tags: 15-20 px across at the recording's 1 m through this lens. Before
  // the saddle refinement's blur was capped by the small square (src/detect/grid_prediction.cc)
  // the corners were 0.17 px RMS off here, and the intrinsics step's ds-none fit went to xi = 0,
  // fu 194.5.
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  testing::TempDir dir;
  const testing::RenderedRecording recording = testing::RenderRecording(s, dir);
  ASSERT_GE(recording.frames, 100);
  const testing::DetectedCorners d = testing::DetectAgainstTruth(recording, dir.File("detect"));
  ASSERT_FALSE(d.observations_path.empty());
  // Measured: 22,369 of 23,040 corners, RMS 0.0230 px, max 0.26 px. Bounds: 95% and twice the RMS.
  EXPECT_GT(d.found, 0.95 * recording.truth.size());
  EXPECT_LT(d.errors.rms_px, 0.05);

  const std::string intrinsics = dir.File("intrinsics");
  const testing::ToolResult i = testing::RunTool(
      {"intrinsics", "--observations", d.observations_path, "--target", recording.target_path,
       "--models", "ds-none", "--resolution", "512x512", "--threads", "2", "--quiet", "--out",
       intrinsics});
  ASSERT_EQ(i.exit_code, 0) << i.err;
  const Camchain own = ReadCamchainYaml(intrinsics + "/camchain.yaml");
  ASSERT_EQ(own.size(), 1u);
  const Camera& fitted = own[0].camera;
  const Camera truth = testing::TumViLikeFisheye();
  // ds-none's fu and xi trade against each other over the image's middle; what the corners fix is
  // the focal length near the axis, fu / (1 + xi).
  auto axis_focal = [](const Camera& c) { return c.fu / (1.0 + c.projection_params(0)); };
  std::printf("intrinsics: fu %.2f fv %.2f pu %.2f pv %.2f xi %.4f alpha %.4f, fu / (1 + xi) %.2f "
              "(truth %.2f)\n",
              fitted.fu, fitted.fv, fitted.pu, fitted.pv, fitted.projection_params(0),
              fitted.projection_params(1), axis_focal(fitted), axis_focal(truth));
  // Measured: 193.10 against 193.05 px, pu 254.89, pv 256.92, alpha 0.5929 (fu 159.86 against
  // 158.3, xi -0.1721 against -0.18). Bounds: 0.1% of the focal length (1 mm of the target's
  // distance at 1 m), 0.3 px, 0.02.
  EXPECT_NEAR(axis_focal(fitted) / axis_focal(truth), 1.0, 1e-3);
  EXPECT_NEAR(fitted.pu, truth.pu, 0.3);
  EXPECT_NEAR(fitted.pv, truth.pv, 0.3);
  EXPECT_NEAR(fitted.projection_params(1), truth.projection_params(1), 0.02);

  const testing::RigError e = testing::CalibrateAgainstTruth(
      s, recording, d.observations_path, intrinsics + "/camchain.yaml", dir.File("calibrate"));
  // Measured: 0.0106 deg, 0.72 mm, 0.012 ms, against calibrate's accuracy targets.
  testing::ExpectWithinCalibrateTargets(e);
}

}  // namespace
}  // namespace splinecal
