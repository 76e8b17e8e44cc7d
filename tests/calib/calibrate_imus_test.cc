// `calibrate` with two IMUs (calib/several_imus_round_trip.h), and a further IMU refused.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calib/several_imus_round_trip.h"
#include "splinecal/error.h"

namespace splinecal {
namespace {

using testing::kImu1;

TEST(CalibrateImus, TwoImusRoundTrip) { testing::ExpectRoundTrip({kImu1}); }

// A further IMU at another rate is refused in plain words naming it.
TEST(CalibrateImus, AnotherRateRefused) {
  testing::ScenarioOptions o;
  o.closed_form = true;
  o.duration_s = 3.0;
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  FurtherImu imu = testing::Simulate(s, 3.0, kImu1);
  std::vector<ImuSample> every_other;
  for (size_t k = 0; k < imu.samples.size(); k += 2) every_other.push_back(imu.samples[k]);
  imu.samples = every_other;  // 100 Hz
  CalibrateOptions options = testing::FastOptions();
  options.further_imus.push_back(imu);
  try {
    Calibrate(s.imu, s.observations, s.start, &s.target, options);
    FAIL() << "not refused";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("imu seed 11"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("the reference's rate"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace splinecal

namespace splinecal {
namespace {

// The lever-arm guard (CalibrateOptions::max_lever_arm_std_m): with a bound below what 3 s of
// this motion determine (the accelerometer's information gives 0.43 mm here, the bound is
// 1 um), the lever arm is held at 0 exactly, reported without a std, and a warning names the IMU;
// the rotation and the time offset are still estimated.
TEST(CalibrateImus, UndeterminedLeverArmHeldWithAWarning) {
  testing::ScenarioOptions o;
  o.closed_form = true;
  o.duration_s = 3.0;
  o.line_delay_s = 0.0;
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  CalibrateOptions options = testing::FastOptions();
  options.keep_residuals = false;
  options.further_imus.push_back(testing::Simulate(s, 3.0, testing::kImu1));
  options.max_lever_arm_std_m = 1e-6;
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  ASSERT_EQ(r.further_imus.size(), 1u);
  const FurtherImuEstimate& e = r.further_imus[0];
  EXPECT_TRUE(e.lever_arm_held);
  EXPECT_EQ(e.calibration.intrinsics.r_b, Eigen::Vector3d::Zero());
  EXPECT_TRUE(std::isnan(e.r_b_std_m.x()));
  EXPECT_TRUE(std::isfinite(e.time_offset_std_s));
  bool warned = false;
  for (const std::string& w : r.warnings) {
    if (w.find("imu seed 11") != std::string::npos && w.find("lever arm") != std::string::npos) {
      warned = true;
      std::printf("%s\n", w.c_str());
    }
  }
  EXPECT_TRUE(warned);
}

}  // namespace
}  // namespace splinecal
