#include "splinecal/calib/calibrate.h"

#include <cmath>
#include <cstdio>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "calib/calibrate_test_scenario.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

constexpr double kPi = 3.14159265358979323846;

struct Errors {
  Eigen::Vector3d rotation_deg;
  Eigen::Vector3d translation_m;
  double timeshift_s;
  double line_delay_s;
};

Errors ErrorsOf(const CameraCalibration& estimate, const CameraCalibration& truth) {
  Errors e;
  e.rotation_deg = (truth.T_cam_imu.so3().inverse() * estimate.T_cam_imu.so3()).Log() * 180.0 / kPi;
  e.translation_m = estimate.T_cam_imu.translation() - truth.T_cam_imu.translation();
  e.timeshift_s = estimate.timeshift_cam_imu_s - truth.timeshift_cam_imu_s;
  e.line_delay_s = estimate.line_delay_s - truth.line_delay_s;
  return e;
}

void Print(const char* name, const CalibrationResult& r, const Errors& e) {
  const CameraEstimate& c = r.cameras[0];
  std::printf("%s: rotation error [%.4f %.4f %.4f] deg (std %.4f %.4f %.4f), translation error "
              "[%.2f %.2f %.2f] mm (std %.2f %.2f %.2f), time offset error %.4f ms (std %.4f), "
              "line delay error %.3f%% (std %.3f us), rms %.3f px, sigma %.3f px, %d iterations, "
              "%d rounds, init %.1f s, solve %.1f s, covariance %.1f s\n",
              name, e.rotation_deg.x(), e.rotation_deg.y(), e.rotation_deg.z(),
              c.rotation_std_deg.x(), c.rotation_std_deg.y(), c.rotation_std_deg.z(),
              1e3 * e.translation_m.x(), 1e3 * e.translation_m.y(), 1e3 * e.translation_m.z(),
              1e3 * c.translation_std_m.x(), 1e3 * c.translation_std_m.y(),
              1e3 * c.translation_std_m.z(), 1e3 * e.timeshift_s, 1e3 * c.timeshift_std_s,
              100.0 * e.line_delay_s / 3e-5, 1e6 * c.line_delay_std_s, r.reprojection_rms_px,
              r.pixel_sigma_px, r.iterations, r.rounds, r.initialisation_time_s, r.solve_time_s,
              r.covariance_time_s);
  for (const std::string& w : r.warnings) std::printf("  warning: %s\n", w.c_str());
}

TEST(Calibrate, RollingShutterRoundTripShort) {
  testing::ScenarioOptions o;
  o.duration_s = 20.0;
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  CalibrateOptions options;
  options.rolling_shutter = true;
  options.num_threads = 2;
  options.progress = [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); };
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  const Errors e = ErrorsOf(r.cameras[0].calibration, s.truth[0]);
  Print("rolling shutter 20 s", r, e);
  EXPECT_LT(e.rotation_deg.norm(), 0.05);
  EXPECT_LT(e.translation_m.norm(), 0.002);
  EXPECT_LT(std::abs(e.timeshift_s), 1e-4);
  EXPECT_LT(std::abs(e.line_delay_s), 0.01 * 3e-5);
}

}  // namespace
}  // namespace splinecal
