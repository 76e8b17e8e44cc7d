// CalibrateOptions::imu_model_held: the named IMU-model parameters stay at nominal and get no std,
// the others are estimated; a name the model does not have is refused. On the calibrate tests'
// simulated sequence (calib/calibrate_test_scenario.h), 8 s, an ideal IMU.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/error.h"
#include "splinecal/lie/so3.h"

namespace splinecal {
namespace {

testing::CalibrationScenario ShortScenario() {
  testing::ScenarioOptions o;
  o.duration_s = 8.0;
  o.line_delay_s = 0.0;
  return testing::MakeCalibrationScenario(o);
}

TEST(CalibrateImuModelHeld, HeldEntriesStayNominalWithoutStd) {
  const testing::CalibrationScenario s = ShortScenario();
  CalibrateOptions options = testing::FastOptions();
  options.imu_model = ImuModelKind::kScaleMisalignment;
  options.imu_model_held = {"A", "C_gyro_i(z)"};  // a whole matrix and one entry
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  ASSERT_TRUE(r.covariance_ok);
  const ImuIntrinsicsd& p = r.imu_model.intrinsics;
  const ImuModelStd& d = r.imu_model_std;
  EXPECT_EQ(p.A, Eigen::Matrix3d::Zero());
  for (int k = 0; k < 9; ++k) EXPECT_TRUE(std::isnan(d.A(k / 3, k % 3))) << "A entry " << k;
  // C_gyro_i = Exp(phi) with phi_z held at 0: Log gives it back to rounding.
  const Eigen::Vector3d phi = SO3d::FromMatrix(p.C_gyro_i).Log();
  EXPECT_LT(std::abs(phi.z()), 1e-12);
  EXPECT_TRUE(std::isnan(d.C_gyro_i_deg.z()));
  EXPECT_GT(d.C_gyro_i_deg.x(), 0.0);  // the others estimated, with a std
  EXPECT_GT(d.C_gyro_i_deg.y(), 0.0);
  EXPECT_GT(d.M_g(0, 0), 0.0);
  EXPECT_NE(p.M_g(0, 0), 1.0);
}

TEST(CalibrateImuModelHeld, ANameTheModelDoesNotHaveIsRefused) {
  const testing::CalibrationScenario s = ShortScenario();
  CalibrateOptions options = testing::FastOptions();
  options.imu_model = ImuModelKind::kScaleMisalignment;
  for (const char* name : {"B", "ry_i", "M_a(0,1)"}) {  // unknown; size effect only; upper triangle
    options.imu_model_held = {name};
    try {
      Calibrate(s.imu, s.observations, s.start, &s.target, options);
      ADD_FAILURE() << name << " was accepted";
    } catch (const Error& e) {
      EXPECT_EQ(std::string(e.what()), std::string("imu_model_held: ") + name +
                                           " is not a parameter of the scale-misalignment model");
    }
  }
}

}  // namespace
}  // namespace splinecal
