// detect, then calibrate: a simulated camera-IMU recording rendered into real image files
// (tests/detect/render_aprilgrid.h), the corners found by `splinecal detect`, and its
// observations.csv given unchanged to `splinecal calibrate`, which must give the rig back.
#include <gtest/gtest.h>

#include <cmath>

#include "detect/rendered_recording.h"
#include "splinecal/io/camchain_yaml.h"
#include "testing/run_tool.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

TEST(DetectThenCalibrate, ImagesOfASimulatedRecordingGiveTheRigBack) {
  const testing::CalibrationScenario s =
      testing::MakeCalibrationScenario(testing::RenderedScenarioOptions(6.0));
  testing::TempDir dir;
  const std::string camchain = dir.Write("camchain.yaml", CamchainYamlText(s.start));
  const testing::RenderedRecording recording = testing::RenderRecording(s, dir);
  ASSERT_GE(recording.frames, 100);
  const testing::DetectedCorners d = testing::DetectAgainstTruth(recording, dir.File("detect"));
  ASSERT_FALSE(d.observations_path.empty());
  // Measured: 17,105 of 17,209 corners (the rest on tags the image border cuts), error RMS
  // 0.0104 px, max 0.040 px. Bounds at 3 to 5 times that: 95% found, RMS 0.03 px, no corner
  // 0.2 px off (a wrong id would be a tag pitch, tens of pixels, off).
  EXPECT_GT(d.found, 0.95 * recording.truth.size());
  EXPECT_LT(d.errors.max_px, 0.2);
  EXPECT_LT(d.errors.rms_px, 0.03);

  const testing::RigError e = testing::CalibrateAgainstTruth(
      s, recording, d.observations_path, camchain, dir.File("calibrate"));
  // Measured: 0.011 deg, 0.28 mm, 0.003 ms, against calibrate's accuracy targets.
  testing::ExpectWithinCalibrateTargets(e);
}

}  // namespace
}  // namespace splinecal
