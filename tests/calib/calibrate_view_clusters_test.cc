// calibrate's cluster-robust covariance over kinds of target view (estimation/view_clusters.h,
// src/calib/calibration_results.cc): the target frames' corners re-estimate the intrinsics, and a
// lens the model does not quite describe pulls them, and the camera's pose with them, apart by
// kind of view, which the 1 s time windows do not see. Simulated: EuRoC's cam0 with the
// intrinsics free, its lens exact (radtan) or with radtan's k3 = kMisfitK3, which the model
// (k1 k2 p1 p2) lacks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "calib/camera_test_scene.h"
#include "splinecal/calib/calibrate.h"

namespace splinecal {
namespace {

constexpr double kMisfitK3 = 0.01;

struct CalibrationRun {
  CalibrationResult result;
  testing::Errors errors;
  IntrinsicsVector intrinsics_error;
};

CalibrationRun CalibrateWithK3(double k3, bool view_clusters) {
  testing::ScenarioOptions o;
  o.duration_s = 8.0;
  o.line_delay_s = 0.0;
  Camera truth = testing::EurocCamera();
  truth.distortion_coeffs(4) = k3;
  o.camera = truth;
  testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  s.start[0].camera.distortion_coeffs(4) = 0.0;  // the model: k1 k2 p1 p2 only
  CalibrateOptions options = testing::FastOptions();
  options.intrinsics = ParameterMode::kFree;
  options.covariance.view_clusters = view_clusters;
  CalibrationRun run;
  run.result = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  run.errors = testing::ErrorsOf(run.result.cameras[0].calibration, s.truth[0]);
  run.intrinsics_error =
      run.result.cameras[0].calibration.camera.intrinsics() - s.truth[0].camera.intrinsics();
  return run;
}

void PrintRun(const char* name, const CalibrationRun& run) {
  const CameraEstimate& c = run.result.cameras[0];
  testing::Print(name, run.result, run.errors);
  std::printf("  view clusters %d, std inflation %.2f; fu error %.3f std %.3f, pu error %.3f "
              "std %.3f\n",
              run.result.view_clusters, run.result.std_inflation, run.intrinsics_error(0),
              c.intrinsics_std(0), run.intrinsics_error(2), c.intrinsics_std(2));
}

TEST(CalibrateViewClusters, Measure) {
  for (double k3 : {0.0, kMisfitK3}) {
    for (bool view : {false, true}) {
      const CalibrationRun run = CalibrateWithK3(k3, view);
      char name[64];
      std::snprintf(name, sizeof(name), "k3 %.3f, view clusters %s", k3, view ? "on" : "off");
      PrintRun(name, run);
    }
  }
}

}  // namespace
}  // namespace splinecal
