// `calibrate` estimating Kalibr's scale-misalignment IMU model (CalibrateOptions::imu_model) on a
// simulated sequence (calib/calibrate_test_scenario.h: 20 s of the lively target-viewing
// trajectory, 200 Hz ADIS16448-like IMU noise, 20 Hz camera, fixed seed) whose IMU readings went
// through a miscalibrated IMU: gyro' = M_g C_gyro_i gyro + A C_gyro_i accel, accel' = M_a accel
// (imu/scale_misalignment_model.h with C_i_b = I, r_b = 0). Applied to the noisy readings, the
// model also maps the biases and the noise: the biases become M_g C_gyro_i b_g + A C_gyro_i b_a
// and M_a b_a, which the (spline) biases absorb, and the noise changes by ~1%, so the truth of
// M_a, M_g, A and C_gyro_i is exactly the values applied.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/lie/so3.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

// Within 3 reported standard deviations of the truth, entry by entry (a 3-sigma bound of a
// Gaussian: about 1 in 370 entries outside by chance; 27 entries here with a fixed seed).
constexpr double kSigmas = 3.0;
// The standard deviations must mean something: below a quarter of a consumer MEMS IMU's errors
// (~1% of scale and ~1 deg of misalignment, Rehder et al., ICRA 2016), so that such an error
// stands out at 4 std: 2.5e-3 for an entry of M_a, M_g, 0.25 deg for C_gyro_i. A is determined
// to ~2e-4 (rad/s)/(m/s^2) here (its z column least: the z specific force is mostly gravity):
// enough for a poor gyro's g-sensitivity (1e-3), not for a good one's (0.1 deg/s/g = 1.7e-4);
// the bound is 5e-4.
constexpr double kMaxMatrixStd = 2.5e-3;
constexpr double kMaxAStd = 5e-4;
constexpr double kMaxRotationStdDeg = 0.25;

void ExpectEntriesWithin(const char* name,
                         const Eigen::Matrix3d& estimate,
                         const Eigen::Matrix3d& truth,
                         const Eigen::Matrix3d& std_dev,
                         double max_std,
                         bool lower_triangle) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      if (lower_triangle && c > r) {
        EXPECT_EQ(estimate(r, c), 0.0) << name;
        continue;
      }
      const double s = std_dev(r, c);
      std::printf("%s(%d,%d): estimate %.6f truth %.6f error %+.2e std %.2e (%+.2f std)\n", name, r,
                  c, estimate(r, c), truth(r, c), estimate(r, c) - truth(r, c), s,
                  (estimate(r, c) - truth(r, c)) / s);
      EXPECT_GT(s, 0.0) << name << "(" << r << "," << c << ")";
      EXPECT_LT(s, max_std) << name << "(" << r << "," << c << ")";
      EXPECT_LE(std::abs(estimate(r, c) - truth(r, c)), kSigmas * s)
          << name << "(" << r << "," << c << ")";
    }
  }
}

TEST(CalibrateImuModel, ScaleMisalignmentRoundTrip) {
  testing::ScenarioOptions o;
  o.duration_s = 20.0;
  o.line_delay_s = 0.0;
  testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  // A consumer-grade IMU (Rehder et al.'s MPU9150: scale errors up to 1%, misalignment up to
  // 1 deg ~ 0.017).
  Eigen::Matrix3d M_a;
  M_a << 1.008, 0.0, 0.0, 0.006, 0.993, 0.0, -0.009, 0.004, 1.011;
  Eigen::Matrix3d M_g;
  M_g << 0.991, 0.0, 0.0, -0.007, 1.012, 0.0, 0.005, -0.010, 1.004;
  Eigen::Matrix3d A;
  A << 4e-4, -2e-4, 1e-4, 3e-4, -5e-4, 2e-4, -1e-4, 2e-4, 3e-4;
  const Eigen::Matrix3d C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.004, -0.006, 0.003)).matrix();
  for (ImuSample& sample : s.imu) {
    const Eigen::Vector3d gyro = sample.gyro;
    const Eigen::Vector3d accel = sample.accel;
    sample.gyro = M_g * C_gyro_i * gyro + A * C_gyro_i * accel;
    sample.accel = M_a * accel;
  }
  CalibrateOptions options = testing::FastOptions();
  options.imu_model = ImuModelKind::kScaleMisalignment;
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  ASSERT_TRUE(r.covariance_ok);
  EXPECT_EQ(r.imu_model.model, ImuModelKind::kScaleMisalignment);
  const ImuIntrinsicsd& p = r.imu_model.intrinsics;
  const ImuModelStd& d = r.imu_model_std;
  ExpectEntriesWithin("M_a", p.M_a, M_a, d.M_a, kMaxMatrixStd, true);
  ExpectEntriesWithin("M_g", p.M_g, M_g, d.M_g, kMaxMatrixStd, true);
  ExpectEntriesWithin("A", p.A, A, d.A, kMaxAStd, false);
  const Eigen::Vector3d rotation_error = SO3d::FromMatrix(C_gyro_i.transpose() * p.C_gyro_i).Log();
  for (int a = 0; a < 3; ++a) {
    std::printf("C_gyro_i axis %d: error %+.4f deg std %.4f deg\n", a,
                rotation_error[a] * kRadToDeg, d.C_gyro_i_deg[a]);
    EXPECT_LT(d.C_gyro_i_deg[a], kMaxRotationStdDeg);
    EXPECT_LE(std::abs(rotation_error[a]) * kRadToDeg, kSigmas * d.C_gyro_i_deg[a]);
  }
  // The camera's extrinsic and time offset within 3 std of the truth. (Not the `calibrated`
  // tests' absolute targets: with the model, the IMU frame is the accelerometer triad's, whose
  // axes the data fix less tightly than a calibrated IMU's: T_cam_imu's rotation std grows from
  // ~0.03 to ~0.09 deg about x and y.)
  const testing::Errors e = testing::ErrorsOf(r.cameras[0].calibration, s.truth[0]);
  testing::Print("scale-misalignment 20 s", r, e);
  const CameraEstimate& c = r.cameras[0];
  ExpectExtrinsicWithinStds(c, e, kSigmas);
  EXPECT_LT(std::abs(e.time_offset_s), kSigmas * c.time_offset_std_s);
}

}  // namespace
}  // namespace splinecal
