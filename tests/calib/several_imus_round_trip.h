// Simulated round trips of `calibrate` with several IMUs on one rig (CalibrateOptions::
// further_imus), shared by calibrate_imus_test.cc and calibrate_imus_slow_test.cc: the
// closed-form trajectory (calib/calibrate_test_scenario.h with closed_form: no spline represents
// it exactly, as on real data), 8 s, 200 Hz ADIS16448-like noise on every IMU, fixed seeds. Each
// further IMU is mounted at a known T_i_b with a known clock offset
// (calib/closed_form_simulation.h): its rotation, lever arm and time offset must come back within
// 3 reported standard deviations, and those standard deviations must be small enough to mean
// something (the bounds below).
#ifndef SPLINECAL_TESTS_CALIB_SEVERAL_IMUS_ROUND_TRIP_H_
#define SPLINECAL_TESTS_CALIB_SEVERAL_IMUS_ROUND_TRIP_H_

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "calib/calibrate_test_checks.h"
#include "calib/calibrate_test_scenario.h"
#include "calib/closed_form_simulation.h"
#include "splinecal/calib/calibrate.h"
#include "splinecal/lie/so3.h"
#include "splinecal/units.h"

namespace splinecal {
namespace testing {

// Within 3 reported standard deviations, per axis (a 3-sigma bound of a Gaussian: 1 in 370 by
// chance per entry; 7 entries per IMU with a fixed seed).
constexpr double kRoundTripSigmas = 3.0;
// The stds must mean something: a rotation to better than 0.1 deg (the camera's T_cam_imu
// warning threshold, CalibrateOptions::warn_rotation_std_deg), a lever arm to better than 5 mm
// (warn_translation_std_m) and a time offset to better than 0.5 ms (half the camera's 1 ms
// warning: the IMUs share a rate, so their offset is known far better than a camera's frame).
constexpr double kMaxRotationStdDeg = 0.1;
// Under a model C_i_b is fixed by the accelerometers alone (the gyro's own rotation goes to
// C_gyro_i): 0.14 deg measured for kImu1 with scale-misalignment; half the 1 deg a C_gyro_i std
// stops meaning anything (estimation/imu_model_observability.cc) bounds it.
constexpr double kMaxModelRotationStdDeg = 0.5;
constexpr double kMaxLeverArmStdM = 0.005;
constexpr double kMaxTimeOffsetStdS = 0.0005;

// The noise seed of further IMU k (1, 2, ...) of a run whose ScenarioOptions::seed is `seed`:
// seed + 200 + (k - 1), the offsets `splinecal simulate` uses (sim/simulation_run.cc), so that
// every sensor of one run draws its own stream: the reference IMU draws from `seed` and the
// camera's pixel noise from seed + 100 (calib/calibrate_test_scenario.h). A further IMU seeded
// with the camera's seed would add to its readings the very numbers the camera adds to its
// corners (both are GaussianSampler streams), noise the estimator assumes independent.
inline uint64_t FurtherImuSeed(uint64_t seed, int k) {
  return seed + 200 + static_cast<uint64_t>(k - 1);
}

struct MountedImu {
  SO3d C_i_b;
  Eigen::Vector3d r_b;
  double time_offset_s;
  Eigen::Vector3d gyro_bias;
  Eigen::Vector3d accel_bias;
  uint64_t seed;
  // Its Kalibr model (FurtherImu::model) and that model's entries (M_a, M_g, A, C_gyro_i,
  // ry_i, rz_i; C_i_b and r_b above), simulated and estimated.
  ImuModelKind model = ImuModelKind::kCalibrated;
  ImuIntrinsicsd intrinsics;
};

inline FurtherImu Simulate(const testing::CalibrationScenario& s, double duration_s, const MountedImu& m) {
  SimulationOptions o;
  o.noise = ImuNoise::Adis16448();
  o.gyro_bias = m.gyro_bias;
  o.accel_bias = m.accel_bias;
  o.seed = m.seed;
  o.imu.model = m.model;
  o.imu.intrinsics = m.intrinsics;
  o.imu.intrinsics.C_i_b = m.C_i_b.matrix();
  o.imu.intrinsics.r_b = m.r_b;
  o.imu.time_offset_s = m.time_offset_s;
  FurtherImu imu;
  imu.name = "imu seed " + std::to_string(m.seed);
  imu.noise = ImuNoise::Adis16448();
  imu.model = m.model;
  imu.samples = testing::SimulateImuFromTrajectory(
      *s.trajectory, s.start_ns, s.start_ns + std::llround(duration_s * 1e9), o);
  return imu;
}

// Every entry of a further IMU's model within 3 stds of the truth (and a std for each).
inline void ExpectEntry(const std::string& what, double estimate, double truth, double std) {
  std::printf("  %s %+.6f truth %+.6f std %.6f\n", what.c_str(), estimate, truth, std);
  EXPECT_TRUE(std::isfinite(std)) << what;
  EXPECT_LE(std::abs(estimate - truth), kRoundTripSigmas * std) << what;
}

inline void ExpectModelRoundTrip(size_t i, const MountedImu& m, const FurtherImuEstimate& e) {
  const ImuIntrinsicsd& p = e.calibration.intrinsics;
  const ImuModelStd& s = e.model_std;
  const std::string imu = "imu" + std::to_string(i) + " ";
  EXPECT_EQ(e.calibration.model, m.model);
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      const std::string rc = "(" + std::to_string(r) + "," + std::to_string(c) + ")";
      if (c <= r) {
        ExpectEntry(imu + "M_a" + rc, p.M_a(r, c), m.intrinsics.M_a(r, c), s.M_a(r, c));
        ExpectEntry(imu + "M_g" + rc, p.M_g(r, c), m.intrinsics.M_g(r, c), s.M_g(r, c));
      }
      ExpectEntry(imu + "A" + rc, p.A(r, c), m.intrinsics.A(r, c), s.A(r, c));
    }
  }
  // C_gyro_i = Exp(phi), phi's std per axis [deg]: the error's rotation vector against it.
  const Eigen::Vector3d phi =
      (SO3d::FromMatrix(m.intrinsics.C_gyro_i).inverse() * SO3d::FromMatrix(p.C_gyro_i)).Log();
  for (int a = 0; a < 3; ++a) {
    ExpectEntry(imu + "C_gyro_i error [deg] axis " + std::to_string(a), phi[a] * kRadToDeg, 0.0,
                s.C_gyro_i_deg[a]);
  }
  if (m.model != ImuModelKind::kScaleMisalignmentSizeEffect) return;
  for (int a = 0; a < 3; ++a) {
    ExpectEntry(imu + "ry_i[" + std::to_string(a) + "]", p.ry_i[a], m.intrinsics.ry_i[a], s.ry_i[a]);
    ExpectEntry(imu + "rz_i[" + std::to_string(a) + "]", p.rz_i[a], m.intrinsics.rz_i[a], s.rz_i[a]);
  }
}

inline void ExpectRoundTrip(const std::vector<MountedImu>& mounted) {
  constexpr double kDurationS = 8.0;
  testing::ScenarioOptions o;
  o.closed_form = true;
  o.duration_s = kDurationS;
  o.line_delay_s = 0.0;
  const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
  CalibrateOptions options = testing::FastOptions();
  options.keep_residuals = false;
  for (const MountedImu& m : mounted) options.further_imus.push_back(Simulate(s, kDurationS, m));
  const CalibrationResult r = Calibrate(s.imu, s.observations, s.start, &s.target, options);
  ASSERT_TRUE(r.covariance_ok);
  ASSERT_EQ(r.further_imus.size(), mounted.size());
  for (size_t i = 0; i < mounted.size(); ++i) {
    const FurtherImuEstimate& e = r.further_imus[i];
    const MountedImu& m = mounted[i];
    EXPECT_FALSE(e.lever_arm_held);
    // C_i_b's error in its right tangent (the std's): C_true^T C_est = Exp(phi).
    const Eigen::Vector3d phi =
        (m.C_i_b.inverse() * SO3d::FromMatrix(e.calibration.intrinsics.C_i_b)).Log();
    const Eigen::Vector3d dr = e.calibration.intrinsics.r_b - m.r_b;
    const double dt = e.calibration.time_offset_s - m.time_offset_s;
    std::printf("imu%zu: rotation error [%+.4f %+.4f %+.4f] deg std [%.4f %.4f %.4f]\n", i + 1,
                phi.x() * kRadToDeg, phi.y() * kRadToDeg, phi.z() * kRadToDeg,
                e.rotation_std_deg.x(), e.rotation_std_deg.y(), e.rotation_std_deg.z());
    std::printf("  lever arm error [%+.2f %+.2f %+.2f] mm std [%.2f %.2f %.2f] mm\n", 1e3 * dr.x(),
                1e3 * dr.y(), 1e3 * dr.z(), 1e3 * e.r_b_std_m.x(), 1e3 * e.r_b_std_m.y(),
                1e3 * e.r_b_std_m.z());
    std::printf("  time offset error %+.4f ms std %.4f ms (initial guess %.4f ms, truth %.4f ms)\n",
                1e3 * dt, 1e3 * e.time_offset_std_s, 1e3 * e.initial_time_offset_s,
                1e3 * m.time_offset_s);
    std::printf("  gyro RMS %.3e rad/s, accel RMS %.3e m/s^2, %d samples\n", e.gyro_rms,
                e.accel_rms, e.num_samples);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LT(e.rotation_std_deg[a], m.model == ImuModelKind::kCalibrated
                                           ? kMaxRotationStdDeg
                                           : kMaxModelRotationStdDeg)
          << "imu" << i + 1 << " axis " << a;
      EXPECT_LE(std::abs(phi[a]) * kRadToDeg, kRoundTripSigmas * e.rotation_std_deg[a])
          << "imu" << i + 1 << " axis " << a;
      EXPECT_LT(e.r_b_std_m[a], kMaxLeverArmStdM) << "imu" << i + 1 << " axis " << a;
      EXPECT_LE(std::abs(dr[a]), kRoundTripSigmas * e.r_b_std_m[a]) << "imu" << i + 1 << " axis " << a;
    }
    EXPECT_LT(e.time_offset_std_s, kMaxTimeOffsetStdS) << "imu" << i + 1;
    EXPECT_LE(std::abs(dt), kRoundTripSigmas * e.time_offset_std_s) << "imu" << i + 1;
    if (m.model != ImuModelKind::kCalibrated) ExpectModelRoundTrip(i + 1, m, e);
  }
  // The camera still calibrates against the reference IMU.
  const testing::Errors e = testing::ErrorsOf(r.cameras[0].calibration, s.truth[0]);
  testing::Print("several IMUs", r, e);
  const CameraEstimate& c = r.cameras[0];
  ExpectExtrinsicWithinStds(c, e, kRoundTripSigmas);
}

// A second IMU turned by ~75 deg, 11 cm from the reference, 2 ms late.
inline const MountedImu kImu1 = {SO3d::Exp(Eigen::Vector3d(0.3, -0.5, 1.2)),
                          Eigen::Vector3d(0.05, -0.10, 0.02),
                          0.002,
                          Eigen::Vector3d(-0.003, 0.002, 0.001),
                          Eigen::Vector3d(-0.04, 0.06, -0.02),
                          11,
                          ImuModelKind::kCalibrated,
                          ImuIntrinsicsd()};
// A third one upside down (~180 deg about x), 7 cm away, 3.5 ms early.
inline const MountedImu kImu2 = {SO3d::Exp(Eigen::Vector3d(3.0, 0.2, -0.1)),
                          Eigen::Vector3d(-0.03, 0.04, -0.05),
                          -0.0035,
                          Eigen::Vector3d(0.001, 0.004, -0.002),
                          Eigen::Vector3d(0.03, -0.05, 0.08),
                          12,
                          ImuModelKind::kCalibrated,
                          ImuIntrinsicsd()};

// kImu1 with a consumer MEMS IMU's errors (Rehder et al., ICRA 2016: scale up to 1%,
// misalignment up to 1 deg), g-sensitivity of 1e-3 (rad/s)/(m/s^2), its gyro triad turned by
// ~1.5 deg, and for the size effect its y and z accelerometers ~1 cm from x.
inline MountedImu WithModel(MountedImu m, ImuModelKind model) {
  m.model = model;
  m.intrinsics.M_a << 1.008, 0.0, 0.0, 0.012, 0.992, 0.0, -0.009, 0.015, 1.011;
  m.intrinsics.M_g << 0.993, 0.0, 0.0, -0.010, 1.009, 0.0, 0.017, -0.006, 0.995;
  m.intrinsics.A << 1e-3, -2e-3, 5e-4, 3e-4, 1.5e-3, -1e-3, 2e-4, -4e-4, 8e-4;
  m.intrinsics.C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.015, -0.02, 0.01)).matrix();
  if (model == ImuModelKind::kScaleMisalignmentSizeEffect) {
    m.intrinsics.ry_i = Eigen::Vector3d(0.004, 0.009, -0.002);
    m.intrinsics.rz_i = Eigen::Vector3d(-0.003, 0.002, 0.008);
  }
  return m;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_CALIB_SEVERAL_IMUS_ROUND_TRIP_H_
