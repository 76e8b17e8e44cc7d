// `calibrate` with two IMUs (calib/several_imus_round_trip.h), and a further IMU refused.
#include <gtest/gtest.h>

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
