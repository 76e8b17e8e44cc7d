// Real data (label "slow"): Kalibr's `scale-misalignment` IMU model estimated by `calibrate` on
// the EuRoC `imu_april` calibration recording (../shared/data, euroc_imu_april/SOURCE.md; 72 s,
// two cameras, the ADIS16448 at 200 Hz), with the command's defaults.
//
// The ADIS16448 is factory calibrated for scale and axis alignment, so the model's estimate must
// come out near nominal: every scale (diagonal of M_a, M_g) within 1%
// of 1 and every misalignment (their off-diagonal entries, in rad) within 0.3 deg of 0, each
// deviation printed with its standard deviation (docs/imu_models.md, "On real data"), and each
// standard deviation below its bound (else the bound would test nothing).
//
// T_cam_imu against the `calibrated` run: the two runs' body frames are different triads. Under
// `calibrated` the gyro and the accelerometer share one frame and the gyro fixes T_cam_imu's
// rotation; under the model the body frame is the accelerometer's and the gyro triad is rotated
// against it by the rotation part R_g of M_g C_gyro_i (its polar decomposition). So the quantity
// both runs determine alike is the camera-to-gyro rotation, R_cam_imu R_g^T under the model: it
// must agree with the calibrated run's R_cam_imu within kMaxGyroFrameStd of that run's std per
// axis (same data, so the difference is the model's extra freedom, not noise: measured
// 2026-11-28 0.43-1.05 std; the bound leaves room for a solver or platform difference).
//
// The translation: both runs put the body origin at the accelerometer triad's (r_b = 0; without
// the size effect Kalibr's model has no other origin), and T_cam_imu's translation is that point
// in the camera frame, independent of the rotation, so it is directly comparable. With the
// camchain's (Kalibr's published) intrinsics held, the model moves it by -0.1, -2.6, -5.4 mm
// (cam0; 0.2, 3.2, 2.9 of the model run's own std), because M_g's x and y scales come out
// +0.48% and +0.44% (3.2 and 2.7 std from 1) while z is -0.21%: the `calibrated` model, which
// trusts the gyro's scale, puts the discrepancy into the lever arm. Holding M_g at nominal
// (everything else of the model estimated) gives a translation within 1 std of the `calibrated`
// run's, asserted below (measured +0.16, -0.24, +0.03 mm: 0.32, 0.38, 0.05 std).
//
// Whose is the 0.45%: the camera's radial distortion, not the gyro's scale (docs/imu_models.md,
// "Whose scale is it"). A radial distortion error changes the image's magnification with the
// radius, which biases the camera's rotation about the axes in the image plane (IMU x and y here)
// but not about the optical axis (IMU z): a rotation about the centre keeps every radius. With
// the intrinsics estimated (`--intrinsics free`, second test) M_g's x and y scales come out
// within 1.5 std of 1 and the two models' translations agree within the model run's std.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include <Eigen/SVD>

#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/lie/so3.h"
#include "splinecal/units.h"
#include "testing/shared_data.h"
#include "testing/tool_allocator.h"

namespace splinecal {
namespace {

constexpr double kMaxScaleError = 0.01;                  // 1% of scale
constexpr double kMaxMisalignmentRad = 0.3 * kDegToRad;  // 0.3 deg
// The M entries must be determined to better than the bounds (measured: scale std 0.02-0.31%,
// misalignment std 0.03-0.20 deg).
constexpr double kMaxScaleStd = kMaxScaleError;
constexpr double kMaxMisalignmentStd = kMaxMisalignmentRad;
constexpr double kMaxGyroFrameStd = 2.0;
// The bar for T_cam_imu's translation, within 1 std per axis (docs/imu_models.md, "On real
// data: EuRoC `imu_april`" and "Whose scale is it"): against the `calibrated` run, met with M_g
// held (measured 0.05-0.38 of the calibrated run's std) and, with the intrinsics estimated,
// against the model run's own std (measured 0.14, 0.96, 0.23 per axis for cam0, 0.14, 0.97,
// 0.24 for cam1).
constexpr double kMaxTranslationStd = 1.0;
// With the intrinsics estimated, M_g's x and y scales: within 2 std of 1 (measured 0.64 and 1.46
// std; with the camchain's intrinsics held 3.2 and 2.7).
constexpr double kMaxGyroScaleSigmas = 2.0;

// The rotation nearest to M (the polar decomposition's orthogonal factor, U V^T of the SVD).
Eigen::Matrix3d NearestRotation(const Eigen::Matrix3d& M) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svd.matrixU() * svd.matrixV().transpose();
}

// The recording, read once for all the calibrations of a test.
struct ImuApril {
  std::vector<ImuSample> imu;
  std::vector<Observation> observations;
  Camchain camchain;
  CalibrationTarget target;
};

const ImuApril& Recording() {
  static const ImuApril* recording = new ImuApril{
      ReadEurocImu(testing::SharedDataPath("euroc_imu_april/imu0.csv")),
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv")),
      ReadCamchainYaml(testing::SharedDataPath("euroc_imu_april/camchain_euroc.yaml")),
      ReadTargetYaml(testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"))};
  return *recording;
}

// A converged calibration of the recording as the starting point of another, in place of the
// PnP-and-fit initial guess (which it saves): the trajectory in the target's frame (the frame
// the problem is solved in; result.control_poses are in the gravity-aligned world,
// calibration_results.cc), gravity there, the biases' means, and each camera's T_cam_imu and
// time offset. The IMU model's parameters start at nominal as always.
CalibrationInitialGuess StartingFrom(const CalibrationResult& r) {
  CalibrationInitialGuess guess;
  guess.layout = r.layout;
  const SE3d T_target_w = r.T_w_target.inverse();
  for (const SE3d& T_w_s : r.control_poses) guess.control_poses.push_back(T_target_w * T_w_s);
  guess.gravity_w = r.gravity_target;
  guess.gyro_bias = r.gyro_bias;
  guess.accel_bias = r.accel_bias;
  guess.camchain = Recording().camchain;
  for (size_t c = 0; c < guess.camchain.size(); ++c) {
    guess.camchain[c].T_cam_imu = r.cameras[c].calibration.T_cam_imu;
    guess.camchain[c].time_offset_s = r.cameras[c].calibration.time_offset_s;
  }
  return guess;
}

// A calibration of the recording: the command's defaults but for these.
struct Setting {
  ImuModelKind model = ImuModelKind::kCalibrated;
  std::vector<std::string> held = {};  // model parameters held at nominal
  bool intrinsics_free = false;   // --intrinsics free (else held at the camchain's)
  bool covariance = true;
};

// From the PnP-and-fit initial guess, or from `start`'s solution when given: then also with the
// IMU noise densities `start` converged to as the given ones (the first round weighted as the
// last; `--imu-noise estimated` still re-estimates them), which saves the rounds that re-weight.
// Measured 2026-11-28 on the calibrated and the M_g-held runs against the same runs from the
// command's own start: 5 rounds -> 3, T_cam_imu moved by at most 0.003 mm (0.005 std), the time
// offset by 4e-5 ms, the stds by at most 0.001 mm (docs/imu_models.md, "The check's cost").
CalibrationResult CalibrateImuApril(const Setting& setting,
                                    const CalibrationResult* start = nullptr) {
  const ImuApril& d = Recording();
  CalibrateOptions options;  // the command's defaults
  options.solver.num_threads = 2;
  options.keep_residuals = false;
  options.imu_model = setting.model;
  options.imu_model_held = setting.held;
  if (setting.intrinsics_free) options.intrinsics = ParameterMode::kFree;
  options.covariance.compute = setting.covariance;
  if (start == nullptr) return Calibrate(d.imu, d.observations, d.camchain, &d.target, options);
  const CalibrationInitialGuess guess = StartingFrom(*start);
  options.model.noise = start->imu_noise.used;
  return Calibrate(d.imu, d.observations, d.camchain, &d.target, options, &guess);
}

void ExpectNearIdentity(const char* name, const Eigen::Matrix3d& M, const Eigen::Matrix3d& std) {
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) {
      const bool scale = r == c;
      const double deviation = scale ? M(r, c) - 1.0 : M(r, c);
      const double bound = scale ? kMaxScaleError : kMaxMisalignmentRad;
      std::printf("%s(%d,%d) = %.6f: %s %+.4f %s (std %.4f)\n",
                  name,
                  r,
                  c,
                  M(r, c),
                  scale ? "scale error" : "misalignment",
                  scale ? 100.0 * deviation : deviation * kRadToDeg,
                  scale ? "%" : "deg",
                  scale ? 100.0 * std(r, c) : std(r, c) * kRadToDeg);
      EXPECT_LE(std::abs(deviation), bound) << name << "(" << r << "," << c << ")";
      EXPECT_GT(std(r, c), 0.0) << name << "(" << r << "," << c << ")";
      EXPECT_LT(std(r, c), scale ? kMaxScaleStd : kMaxMisalignmentStd)
          << name << "(" << r << "," << c << ")";
    }
  }
}

// Each camera's translation of the model run against the calibrated run's, with both runs' stds
// (per axis of t_cam_imu, camera frame).
void PrintTranslationShift(const char* label,
                           const CalibrationResult& model,
                           const CalibrationResult& calibrated) {
  for (size_t cam = 0; cam < model.cameras.size(); ++cam) {
    const CameraEstimate& a = model.cameras[cam];
    const CameraEstimate& b = calibrated.cameras[cam];
    const Eigen::Vector3d d =
        a.calibration.T_cam_imu.translation() - b.calibration.T_cam_imu.translation();
    std::printf("%s: cam%zu translation, model - calibrated %+.3f %+.3f %+.3f mm: %+.2f %+.2f "
                "%+.2f of the calibrated run's std, %+.2f %+.2f %+.2f of the model run's\n",
                label, cam, 1e3 * d[0], 1e3 * d[1], 1e3 * d[2],
                d[0] / b.translation_std_m[0], d[1] / b.translation_std_m[1],
                d[2] / b.translation_std_m[2], d[0] / a.translation_std_m[0],
                d[1] / a.translation_std_m[1], d[2] / a.translation_std_m[2]);
  }
}

// The model, the `calibrated` run and the model with M_g held: the second and third start from
// the model run's solution and noise weights (CalibrateImuApril), and the third computes no
// covariance (its check uses the calibrated run's std; that a held entry gets no std is
// calibrate_imu_model_held_test.cc's).
TEST(CalibrateImuModelEuroc, FactoryCalibratedImuComesOutNearNominal) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const CalibrationResult model = CalibrateImuApril({ImuModelKind::kScaleMisalignment});
  const CalibrationResult calibrated = CalibrateImuApril({ImuModelKind::kCalibrated}, &model);
  ASSERT_TRUE(model.covariance_ok);
  ASSERT_TRUE(calibrated.covariance_ok);
  ASSERT_EQ(model.imu_model.model, ImuModelKind::kScaleMisalignment);
  for (const std::string& w : model.warnings) std::printf("warning: %s\n", w.c_str());
  const ImuIntrinsicsd& p = model.imu_model.intrinsics;
  ExpectNearIdentity("M_a", p.M_a, model.imu_model_std.M_a);
  ExpectNearIdentity("M_g", p.M_g, model.imu_model_std.M_g);
  for (int r = 0; r < 3; ++r) {
    std::printf("A row %d [(rad/s)/(m/s^2)]: %+.2e %+.2e %+.2e (std %.1e %.1e %.1e)\n",
                r,
                p.A(r, 0),
                p.A(r, 1),
                p.A(r, 2),
                model.imu_model_std.A(r, 0),
                model.imu_model_std.A(r, 1),
                model.imu_model_std.A(r, 2));
  }
  const Eigen::Vector3d phi_deg = SO3d(Eigen::Quaterniond(p.C_gyro_i)).Log() * kRadToDeg;
  std::printf("C_gyro_i rotation vector [deg]: %+.4f %+.4f %+.4f (std %.4f %.4f %.4f)\n",
              phi_deg[0],
              phi_deg[1],
              phi_deg[2],
              model.imu_model_std.C_gyro_i_deg[0],
              model.imu_model_std.C_gyro_i_deg[1],
              model.imu_model_std.C_gyro_i_deg[2]);

  ASSERT_EQ(model.cameras.size(), calibrated.cameras.size());
  const SO3d R_g(Eigen::Quaterniond(NearestRotation(p.M_g * p.C_gyro_i)));
  for (size_t cam = 0; cam < model.cameras.size(); ++cam) {
    const CameraEstimate& a = model.cameras[cam];
    const CameraEstimate& b = calibrated.cameras[cam];
    const SO3d R_cal_inverse = b.calibration.T_cam_imu.so3().inverse();
    const Eigen::Vector3d d_rot_deg = (R_cal_inverse * a.calibration.T_cam_imu.so3()).Log() * kRadToDeg;
    const Eigen::Vector3d d_gyro_deg =
        (R_cal_inverse * a.calibration.T_cam_imu.so3() * R_g.inverse()).Log() * kRadToDeg;
    const Eigen::Vector3d d_trans =
        a.calibration.T_cam_imu.translation() - b.calibration.T_cam_imu.translation();
    for (int k = 0; k < 3; ++k) {
      const double var_a = a.translation_std_m[k] * a.translation_std_m[k];
      const double var_b = b.translation_std_m[k] * b.translation_std_m[k];
      std::printf(
          "cam%zu axis %d: rotation %+.4f deg, camera to gyro %+.4f deg (std %.4f), "
          "translation %+.3f mm (std calibrated %.3f, model %.3f, difference %.3f)\n",
          cam,
          k,
          d_rot_deg[k],
          d_gyro_deg[k],
          b.rotation_std_deg[k],
          1e3 * d_trans[k],
          1e3 * b.translation_std_m[k],
          1e3 * a.translation_std_m[k],
          1e3 * std::sqrt(std::max(0.0, var_a - var_b)));
      EXPECT_LE(std::abs(d_gyro_deg[k]), kMaxGyroFrameStd * b.rotation_std_deg[k])
          << "cam" << cam << " axis " << k;
    }
  }
  std::printf("time offset: model %+.4f ms, calibrated %+.4f ms (std %.4f ms)\n",
              1e3 * model.cameras[0].calibration.time_offset_s,
              1e3 * calibrated.cameras[0].calibration.time_offset_s,
              1e3 * calibrated.cameras[0].time_offset_std_s);

  // The gyro's M_g held at nominal: the translation is the calibrated run's.
  const CalibrationResult held_m_g = CalibrateImuApril(
      {ImuModelKind::kScaleMisalignment, {"M_g"}, /*intrinsics_free=*/false, /*covariance=*/false},
      &model);
  for (size_t cam = 0; cam < held_m_g.cameras.size(); ++cam) {
    const Eigen::Vector3d d = held_m_g.cameras[cam].calibration.T_cam_imu.translation() -
                              calibrated.cameras[cam].calibration.T_cam_imu.translation();
    for (int k = 0; k < 3; ++k) {
      const double std_m = calibrated.cameras[cam].translation_std_m[k];
      std::printf("M_g held: cam%zu axis %d translation %+.3f mm (%.2f std)\n",
                  cam, k, 1e3 * d[k], d[k] / std_m);
      EXPECT_LE(std::abs(d[k]), kMaxTranslationStd * std_m) << "cam" << cam << " axis " << k;
    }
  }
}

// The intrinsics estimated with everything else (`--intrinsics free`, both runs): the gyro's x
// and y scales lose the 0.45% they show with the camchain's intrinsics held (the camera's radial
// distortion, file comment), and the two models' translations agree within the model run's std
// (the bar of docs/imu_models.md; against the calibrated run's own, smaller std y is 1.2: measured
// 2026-11-28 -0.16, -1.26, +0.68 mm, docs/imu_models.md). The calibrated run starts from the
// model run's solution.
TEST(CalibrateImuModelEuroc, WithTheIntrinsicsEstimatedTheModelsAgree) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const CalibrationResult model =
      CalibrateImuApril({ImuModelKind::kScaleMisalignment, {}, /*intrinsics_free=*/true});
  const CalibrationResult calibrated =
      CalibrateImuApril({ImuModelKind::kCalibrated, {}, /*intrinsics_free=*/true}, &model);
  ASSERT_TRUE(model.covariance_ok);
  ASSERT_TRUE(calibrated.covariance_ok);
  ASSERT_TRUE(model.cameras[0].intrinsics_estimated);
  const ImuIntrinsicsd& p = model.imu_model.intrinsics;
  const Eigen::Matrix3d& M_g_std = model.imu_model_std.M_g;
  for (int k = 0; k < 3; ++k) {
    std::printf("M_g(%d,%d): scale error %+.4f %% (std %.4f %%, %.2f std)\n", k, k,
                100.0 * (p.M_g(k, k) - 1.0), 100.0 * M_g_std(k, k),
                (p.M_g(k, k) - 1.0) / M_g_std(k, k));
  }
  for (size_t cam = 0; cam < model.cameras.size(); ++cam) {
    const Camera& m = model.cameras[cam].calibration.camera;
    const Camera& c = calibrated.cameras[cam].calibration.camera;
    std::printf("cam%zu fu fv pu pv: model %.2f %.2f %.2f %.2f, calibrated %.2f %.2f %.2f %.2f\n",
                cam, m.fu, m.fv, m.pu, m.pv, c.fu, c.fv, c.pu, c.pv);
  }
  // x and y: the axes in the camera's image plane (cam z is IMU z within 1.5 deg).
  for (int k = 0; k < 2; ++k) {
    EXPECT_LE(std::abs(p.M_g(k, k) - 1.0), kMaxGyroScaleSigmas * M_g_std(k, k)) << k;
  }
  PrintTranslationShift("intrinsics free", model, calibrated);
  for (size_t cam = 0; cam < model.cameras.size(); ++cam) {
    const Eigen::Vector3d d = model.cameras[cam].calibration.T_cam_imu.translation() -
                              calibrated.cameras[cam].calibration.T_cam_imu.translation();
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(d[k]), kMaxTranslationStd * model.cameras[cam].translation_std_m[k])
          << "cam" << cam << " axis " << k;
    }
  }
}

// A study (disabled: six calibrations, about 3 min on the shared machine; run with
// --gtest_also_run_disabled_tests): which of the model's parameters moves the translation. Each
// group held at nominal in turn, the rest of the model estimated; cam0's translation against the
// `calibrated` run. Measured 2026-11-28 (docs/imu_models.md): only M_g brings it back (+0.16,
// -0.24, +0.03 mm); with A, C_gyro_i, M_a or M_a's off-diagonals held the z shift stays -5.1 to
// -5.5 mm and the y shift -2.3 to -2.7 mm.
TEST(CalibrateImuModelEuroc, DISABLED_WhatMovesTheTranslation) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const CalibrationResult calibrated = CalibrateImuApril({ImuModelKind::kCalibrated});
  const std::vector<std::vector<std::string>> held_sets = {
      {"A"}, {"C_gyro_i"}, {"M_a(1,0)", "M_a(2,0)", "M_a(2,1)"}, {"M_a"}, {"M_g"}};
  for (const std::vector<std::string>& held : held_sets) {
    const CalibrationResult model = CalibrateImuApril({ImuModelKind::kScaleMisalignment, held});
    std::string names;
    for (const std::string& n : held) names += n + " ";
    const Eigen::Vector3d d = model.cameras[0].calibration.T_cam_imu.translation() -
                              calibrated.cameras[0].calibration.T_cam_imu.translation();
    const Eigen::Vector3d std_m = calibrated.cameras[0].translation_std_m;
    std::printf("held %s: cam0 translation change %+.3f %+.3f %+.3f mm (model std %.3f %.3f %.3f)\n",
                names.c_str(), 1e3 * d[0], 1e3 * d[1], 1e3 * d[2],
                1e3 * model.cameras[0].translation_std_m[0],
                1e3 * model.cameras[0].translation_std_m[1],
                1e3 * model.cameras[0].translation_std_m[2]);
    // Holding M_g removes the shift; holding anything else leaves the z shift beyond 3 std.
    if (held.front() == "M_g") {
      EXPECT_LE(d.cwiseQuotient(std_m).cwiseAbs().maxCoeff(), kMaxTranslationStd);
    } else {
      EXPECT_GT(std::abs(d[2]), 3.0 * std_m[2]) << names;
    }
  }
}

}  // namespace
}  // namespace splinecal
