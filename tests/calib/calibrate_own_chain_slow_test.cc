// Real data (label "slow"): the user's own chain on EuRoC's imu_april (../shared/data,
// euroc_imu_april/SOURCE.md and REFERENCE.md), with no published intrinsics anywhere: `splinecal
// intrinsics` on the recording's corners (both cameras, one model), then `splinecal calibrate` on
// its camchain.yaml with the default settings (intrinsics and camera chain enter as priors with
// the intrinsics step's covariance; docs/calibrate.md, "Intrinsics and camera chain: held,
// prior, free"). Both steps run through the command line, so the covariance the test uses is
// whatever the real intrinsics step writes today. The model is ds-none, which fits this lens
// (pinhole-equi gives the same T_cam_imu to 0.005 deg and 0.1 mm; pinhole-radtan misfits the
// image border and lands 6.3-6.6 mm from basalt).
//
//   * Whole recording: camera positions within the 8 mm target of basalt, the stereo baseline
//     within 1 mm of the published 110.074 mm and 3 of its std, and the rotation about the IMU's
//     y and z within 3 own std of the published-camchain run.
//   * Halves: each half runs its own chain; the rotation about the IMU's y and z and the
//     translation x and y within 3 combined std, the RMS of the 12 normalised differences at
//     least 0.25, and the two components not met held below their measured level.
//   * Halves with --intrinsics consider (the intrinsics held, their covariance carried): ten of
//     the twelve components within 3 combined std, the translation z held below its level.
//   * Every target point estimated (--target-deformation points, the refined target.yaml into
//     calibrate): within 0.35 deg and 8 mm of basalt, the baseline, the halves within 3 combined
//     std but the rotation about the IMU's x (held below 4.5).
//   * DISABLED, not met by any model (figures beside each): the whole T_cam_imu within 3 own std
//     of the published-camchain run, and all of the halves' T_cam_imu within 3 combined std.
//     Enable them when the principal point and focal length agree with the references and
//     between the halves within their std (docs/calibrate.md, "On EuRoC's imu_april").
#include <gtest/gtest.h>

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
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
#include "testing/tool_allocator.h"

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

std::vector<std::string> CalibrateArgs(
    const std::string& imu, const std::string& observations, const std::string& camchain,
    const std::string& out,
    const std::string& target = testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml")) {
  return {"calibrate", "--imu",      imu,      "--observations", observations, "--target",
          target,      "--camchain", camchain, "--threads",      "2",          "--quiet",
          "--out",     out};
}

// The chain's target: the file's (empty) or, with "points" or "points-in-plane", every point
// estimated by the intrinsics step, whose refined target.yaml calibrate then reads.
struct ChainOptions {
  std::string intrinsics_mode;  // calibrate's --intrinsics; empty: the default
  std::string target_deformation;
};

// intrinsics with `model` for both cameras, then calibrate with its camchain.yaml and the
// defaults (`intrinsics_mode` empty) or --intrinsics intrinsics_mode, into dir/intrinsics and
// dir/calibrate.
Calibration OwnChain(const std::string& imu, const std::string& observations,
                     const std::string& model, const std::string& dir,
                     const ChainOptions& chain = {}) {
  const std::string& intrinsics_mode = chain.intrinsics_mode;
  std::vector<std::string> intrinsics_args = {
      "intrinsics", "--observations", observations, "--target",
      testing::SharedDataPath("euroc_imu_april/aprilgrid.yaml"), "--models",
      model + "," + model, "--resolution", "752x480", "--threads", "2", "--quiet", "--out",
      dir + "/intrinsics"};
  if (!chain.target_deformation.empty()) {
    intrinsics_args.insert(intrinsics_args.end(),
                           {"--target-deformation", chain.target_deformation});
  }
  const testing::ToolResult intrinsics = testing::RunTool(intrinsics_args);
  EXPECT_EQ(intrinsics.exit_code, 0) << intrinsics.err;
  std::vector<std::string> args =
      chain.target_deformation.empty()
          ? CalibrateArgs(imu, observations, dir + "/intrinsics/camchain.yaml", dir + "/calibrate")
          : CalibrateArgs(imu, observations, dir + "/intrinsics/camchain.yaml",
                          dir + "/calibrate", dir + "/intrinsics/target.yaml");
  if (!intrinsics_mode.empty()) args.insert(args.end(), {"--intrinsics", intrinsics_mode});
  const testing::ToolResult calibrate = testing::RunTool(args);
  EXPECT_EQ(calibrate.exit_code, 0) << calibrate.err;
  // The defaults with a covariance in the camchain: both priors.
  const YamlDocument result(dir + "/calibrate/result.yaml");
  EXPECT_EQ(result.String("camera_chain"), "prior");
  EXPECT_EQ(result.String("cameras/cam0/intrinsics_mode"),
            intrinsics_mode.empty() ? "prior" : intrinsics_mode);
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

// Rotation angle [deg] of T_cam_imu from a reference T_imu_cam.
double RotationFromDeg(const SE3d& T_cam_imu, const SE3d& T_imu_cam_ref) {
  return (T_cam_imu * T_imu_cam_ref).so3().Log().norm() * kRadToDeg;
}

// Distance [m] of the camera position in the IMU frame from a reference T_imu_cam's.
double PositionFromM(const SE3d& T_cam_imu, const SE3d& T_imu_cam_ref) {
  return (T_cam_imu.inverse().translation() - T_imu_cam_ref.translation()).norm();
}

void PrintDistance(const char* name, const SE3d& T_cam_imu, const SE3d& T_imu_cam_ref) {
  std::printf("  from %s: %.3f deg, %.2f mm\n", name, RotationFromDeg(T_cam_imu, T_imu_cam_ref),
              1e3 * PositionFromM(T_cam_imu, T_imu_cam_ref));
}

// basalt's T_imu_cam of cam0 and cam1 (REFERENCE.md).
const SE3d& Basalt(int cam) {
  static const SE3d basalt[2] = {
      SE3d(SO3d::FromQuaternion(Eigen::Quaterniond(0.7123126, -0.0072398, 0.0075413, 0.7017845)),
           Eigen::Vector3d(-0.0167748, -0.0689389, 0.0051391)),
      SE3d(SO3d::FromQuaternion(Eigen::Quaterniond(0.7115930, -0.0023361, 0.0130008, 0.7024677)),
           Eigen::Vector3d(-0.0150744, 0.0412627, 0.0031629))};
  return basalt[cam];
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

constexpr const char* kComponentNames[6] = {"rot x", "rot y", "rot z", "t x", "t y", "t z"};
constexpr double kPrintScale[6] = {1, 1, 1, 1e3, 1e3, 1e3};  // deg, mm

// Each half of the recording (cut at the IMU's middle time, as CalibrateEuroc's halves in
// calibrate_euroc_slow_test.cc) runs its own chain with `model` (and calibrate's --intrinsics
// intrinsics_mode, empty: the default). Returns, per camera and component, |T_cam_imu
// difference| / combined reported std (cam0's 6, then cam1's), printed.
std::vector<double> HalvesNormalisedDifferences(const std::string& model,
                                                const ChainOptions& chain = {}) {
  const std::vector<ImuSample> imu =
      ReadEurocImu(testing::SharedDataPath("euroc_imu_april/imu0.csv"));
  const std::vector<Observation> observations =
      ReadObservationsCsv(testing::SharedDataPath("euroc_imu_april/observations.csv"));
  EXPECT_GT(imu.size(), 14000u);
  const int64_t middle = imu.front().t_ns + (imu.back().t_ns - imu.front().t_ns) / 2;
  testing::TempDir dir;
  WriteHalf(imu, observations, imu.front().t_ns, middle, dir.File("imu_1.csv"),
            dir.File("observations_1.csv"));
  WriteHalf(imu, observations, middle, imu.back().t_ns + 1, dir.File("imu_2.csv"),
            dir.File("observations_2.csv"));
  const Calibration first = OwnChain(dir.File("imu_1.csv"), dir.File("observations_1.csv"), model,
                                     dir.File("first"), chain);
  const Calibration second = OwnChain(dir.File("imu_2.csv"), dir.File("observations_2.csv"), model,
                                      dir.File("second"), chain);
  std::vector<double> normalised;
  for (int cam = 0; cam < 2; ++cam) {
    const Eigen::Matrix<double, 6, 1> d = Difference(first.T_cam_imu[cam], second.T_cam_imu[cam]);
    const Eigen::Matrix<double, 6, 1> s =
        (Std(first, cam).array().square() + Std(second, cam).array().square()).sqrt();
    for (int k = 0; k < 6; ++k) {
      normalised.push_back(std::abs(d[k]) / s[k]);
      std::printf("%s cam%d %-6s  difference %9.4f  std %8.4f  |difference|/std %5.2f\n",
                  model.c_str(), cam, kComponentNames[k], d[k] * kPrintScale[k],
                  s[k] * kPrintScale[k], normalised.back());
    }
  }
  return normalised;
}

double Rms(const std::vector<double>& values) {
  double sum_squares = 0.0;
  for (double v : values) sum_squares += v * v;
  return std::sqrt(sum_squares / values.size());
}

double Largest(const std::vector<double>& values) {
  return *std::max_element(values.begin(), values.end());
}

// The whole recording's own chain with `model` and the same calibrate run with the published
// camchain; `ratios` per camera and component |published - own| / the own chain's reported std
// (cam0's 6, then cam1's), printed with the distances to basalt's and Kalibr's calibrations.
struct WholeRecording {
  Calibration own;
  Calibration published;
  std::vector<double> ratios;
};

WholeRecording CompareWithThePublishedCamchainRun(const std::string& model,
                                                  const ChainOptions& chain = {}) {
  testing::TempDir dir;
  const std::string imu = testing::SharedDataPath("euroc_imu_april/imu0.csv");
  const std::string observations = testing::SharedDataPath("euroc_imu_april/observations.csv");
  WholeRecording w;
  w.own = OwnChain(imu, observations, model, dir.File("own"), chain);
  const testing::ToolResult published = testing::RunTool(CalibrateArgs(
      imu, observations, testing::SharedDataPath("euroc_imu_april/camchain_euroc.yaml"),
      dir.File("published")));
  EXPECT_EQ(published.exit_code, 0) << published.err;
  w.published = ReadCalibration(dir.File("published"));
  const Camchain kalibr =
      ReadCamchainYaml(testing::SharedDataPath("euroc_imu_april/camchain_euroc.yaml"));
  std::printf("%s baseline: own chain %.3f mm (std %.3f), published camchain %.3f mm\n",
              model.c_str(), 1e3 * w.own.baseline_m, 1e3 * w.own.baseline_std_m,
              1e3 * w.published.baseline_m);
  for (int cam = 0; cam < 2; ++cam) {
    std::printf("cam%d own chain (%s)\n", cam, model.c_str());
    PrintDistance("basalt", w.own.T_cam_imu[cam], Basalt(cam));
    PrintDistance("Kalibr", w.own.T_cam_imu[cam], kalibr[cam].T_cam_imu.inverse());
    std::printf("cam%d published camchain\n", cam);
    PrintDistance("basalt", w.published.T_cam_imu[cam], Basalt(cam));
    PrintDistance("Kalibr", w.published.T_cam_imu[cam], kalibr[cam].T_cam_imu.inverse());
    const Eigen::Matrix<double, 6, 1> d =
        Difference(w.own.T_cam_imu[cam], w.published.T_cam_imu[cam]);
    const Eigen::Matrix<double, 6, 1> s = Std(w.own, cam);
    for (int k = 0; k < 6; ++k) {
      w.ratios.push_back(std::abs(d[k]) / s[k]);
      std::printf("%s cam%d %-6s  published - own %9.4f  own std %8.4f  ratio %5.2f\n",
                  model.c_str(), cam, kComponentNames[k], d[k] * kPrintScale[k],
                  s[k] * kPrintScale[k], w.ratios.back());
    }
  }
  return w;
}

// The model the data supports (intrinsics --compare-models on every 8th view: ds-none RMS
// 0.4405 px, pinhole-equi 0.4401, pinhole-radtan 0.5086; docs/intrinsics.md). What holds today:
// the positions within the 8 mm target of basalt, the baseline within 1 mm of the published one
// and within 3 of its std, and, against the published-camchain run, the rotation about the IMU's
// y and z axes within 3 own std. The rotation about the IMU's x axis (the camera's y, the axis a
// principal-point shift in u turns) is not: printed, asserted by the DISABLED test below.
TEST(CalibrateOwnChain, DsNonePositionsBaselineAndRotationBesidesThePrincipalPoint) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const WholeRecording w = CompareWithThePublishedCamchainRun("ds-none");
  for (int cam = 0; cam < 2; ++cam) {
    // Measured 3.65 / 3.40 mm (2026-11-28); radtan's own chain 6.3-6.6 mm.
    EXPECT_LE(PositionFromM(w.own.T_cam_imu[cam], Basalt(cam)), 8e-3) << "cam" << cam;
    // Rotation about the IMU's y and z: measured 0.06-0.30 own std.
    EXPECT_LE(w.ratios[6 * cam + 1], 3.0) << "cam" << cam << " rot y";
    EXPECT_LE(w.ratios[6 * cam + 2], 3.0) << "cam" << cam << " rot z";
  }
  // Within 1 mm (the bound in docs/calibrate.md, "Tests"; basalt's baseline, from its camera
  // positions, is 110.23 mm, 0.16 mm from Kalibr's), and the reported std covers the difference.
  // Measured 110.100 +- 0.127 mm.
  EXPECT_NEAR(w.own.baseline_m, kPublishedBaselineM, 1e-3);
  EXPECT_LE(std::abs(w.own.baseline_m - kPublishedBaselineM), 3.0 * w.own.baseline_std_m);
}

// Not met by any model today (2026-11-28, this test's printout): the rotation about the IMU's x
// axis is 0.50 / 0.40 deg (cam0 / cam1) from the published-camchain run at 10.4 / 8.8 own std
// with ds-none (12.2 / 10.0 before calibrate's covariance over kinds of view; pinhole-equi 12.3 /
// 10.0, pinhole-radtan 6.7-6.9 then), translation y 2.7-2.9 mm at 2.9-3.3 std: the principal
// point this recording gives (ds-none cam0 pu 362.2 px after calibrate) is 3.7 px from basalt's
// 365.9, with every model and every processing step (docs/calibrate.md, "Why: the principal
// point"; docs/intrinsics.md, "The principal point of this recording"). With every target
// point free (2026-11-29) cam0's pu comes to 364.6 px and the rotation about x to 0.27 / 0.19 deg
// from the published run, still at 14.3 / 10.8 own std (the test below).
TEST(CalibrateOwnChain, DISABLED_WholeRecordingWithinThreeStdOfThePublishedCamchainRun) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const WholeRecording w = CompareWithThePublishedCamchainRun("ds-none");
  for (size_t i = 0; i < w.ratios.size(); ++i) {
    EXPECT_LE(w.ratios[i], 3.0) << "cam" << i / 6 << " " << kComponentNames[i % 6];
  }
}

// Each component's limit below. Met: the rotation about the IMU's y and z, the translation x
// and y (measured 2026-11-28 with ds-none: at most 2.86 combined std). Not met: the rotation
// about the IMU's x (0.28 / 0.25 deg, cam0 / cam1, at 3.72 / 3.68 combined std) and the
// translation z (15.2 / 14.2 mm at 4.93 / 4.45), held below 4.5 and 6 so that they cannot slide
// back to where they were with the time windows alone (5.14 / 4.59 and 8.30 / 6.88).
constexpr double kHalvesLimit[6] = {4.5, 3.0, 3.0, 3.0, 3.0, 6.0};

// The halves with what holds today: calibrate's covariance over kinds of target view (with its
// 1 s time windows; docs/calibrate.md, "How much to trust the numbers") takes the halves' largest
// normalised difference from 8.30 to 4.93 and their RMS from 3.96 to 2.81.
TEST(CalibrateOwnChain, HalvesAgreeWhereTheIntrinsicsDoNotDecide) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const std::vector<double> normalised = HalvesNormalisedDifferences("ds-none");
  for (size_t i = 0; i < normalised.size(); ++i) {
    EXPECT_LE(normalised[i], kHalvesLimit[i % 6]) << "cam" << i / 6 << " " << kComponentNames[i % 6];
  }
  std::printf("largest |difference|/std: %.2f, RMS %.2f\n", Largest(normalised), Rms(normalised));
  // Honest stds make the 12 normalised differences about unit normal: their mean square is
  // chi-square(12)/12, below 0.25^2 with probability ~1e-6; stds 4x too large put the RMS there.
  EXPECT_GE(Rms(normalised), 0.25) << "reported standard deviations too large";
}

// The intrinsics considered instead of a prior (--intrinsics consider: held at the intrinsics
// step's values, their covariance carried into T_cam_imu's, calib/consider_covariance.h; the
// corners count once). Measured 2026-11-28 with ds-none (docs/calibrate.md, "Considered
// intrinsics"): ten of the twelve components within 3 combined std, the rotation about the IMU's
// x at 1.96 / 1.92 (3.72 / 3.68 with the prior); the translation z is not, 16.9 / 16.0 mm at
// 4.27 / 4.42, held below 5.5 so that it cannot slide back to the prior's level or beyond; RMS
// 2.39 (prior 2.81).
TEST(CalibrateOwnChain, ConsideredIntrinsicsHalvesAgreeExceptTheTranslationAlongTheAxis) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  ChainOptions consider;
  consider.intrinsics_mode = "consider";
  const std::vector<double> normalised = HalvesNormalisedDifferences("ds-none", consider);
  constexpr double kLimit[6] = {3.0, 3.0, 3.0, 3.0, 3.0, 5.5};
  for (size_t i = 0; i < normalised.size(); ++i) {
    EXPECT_LE(normalised[i], kLimit[i % 6]) << "cam" << i / 6 << " " << kComponentNames[i % 6];
  }
  std::printf("largest |difference|/std: %.2f, RMS %.2f\n", Largest(normalised), Rms(normalised));
  // As above: stds 4x too large would put the RMS below 0.25.
  EXPECT_GE(Rms(normalised), 0.25) << "reported standard deviations too large";
}

// Not met by any model today (2026-11-28, this test's printout): ds-none's halves differ in
// translation z by 15.2 / 14.2 mm (cam0 / cam1) at 4.93 / 4.45 combined std and about the IMU's
// x by 0.28 / 0.25 deg at 3.72 / 3.68, RMS 2.81 (with the time windows alone, before calibrate's
// covariance over kinds of view: 8.30 / 6.88 in translation z, RMS 3.96; pinhole-equi then 8.3 /
// 7.7, RMS 4.08; pinhole-radtan 13.6 mm at 4.6-4.8 std, RMS 2.69). A full-matrix robust
// covariance in both steps instead of the per-coordinate scaling (measured, not kept;
// docs/calibrate.md, "The correlations the per-coordinate scaling keeps") gives 4.19 / 3.84 in
// translation z and 3.52 / 3.39 about x, RMS 2.49: the gap is not in the kept correlations.
TEST(CalibrateOwnChain, DISABLED_HalvesAgreeWithinTheirReportedStandardDeviations) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  const std::vector<double> normalised = HalvesNormalisedDifferences("ds-none");
  for (size_t i = 0; i < normalised.size(); ++i) {
    EXPECT_LE(normalised[i], 3.0) << "cam" << i / 6 << " " << kComponentNames[i % 6];
  }
  // Honest stds make the 12 normalised differences about unit normal: their mean square is
  // chi-square(12)/12, below 0.25^2 with probability ~1e-6; stds 4x too large put the RMS there.
  std::printf("largest |difference|/std: %.2f, RMS %.2f\n", Largest(normalised), Rms(normalised));
  EXPECT_GE(Rms(normalised), 0.25) << "reported standard deviations too large";
}

// Every target point estimated with the intrinsics (--target-deformation points; target.yaml
// into calibrate's --target; docs/intrinsics.md, "Every point free"): the target of 0.35 deg and
// 8 mm from basalt is met (measured 2026-11-29: 0.191 / 0.199 deg, 2.90 / 2.83 mm, cam0 / cam1;
// the file's layout 0.438 / 0.422 deg), the baseline 110.197 +- 0.094 mm, and the halves agree
// within 3 combined std but about the IMU's x axis on cam1 (2.86 / 3.87; translation z 1.32 /
// 1.26, which the file's layout puts at 4.93 / 4.45), held below 4.5; RMS 1.78. Against the
// published-camchain run (printed) the rotation about the IMU's x stays 0.27 / 0.19 deg apart at
// 14.3 / 10.8 own std: the published intrinsics' principal point (Kalibr's pu 367.2 px, cam0)
// against this chain's (364.6 px; basalt's 365.9).
TEST(CalibrateOwnChain, FreeTargetMeetsTheReferenceTargetAndTheHalvesNearlyAgree) {
  SPLINECAL_REQUIRE_SHARED_DATA("euroc_imu_april/observations.csv");
  ChainOptions chain;
  chain.target_deformation = "points";
  const WholeRecording w = CompareWithThePublishedCamchainRun("ds-none", chain);
  for (int cam = 0; cam < 2; ++cam) {
    EXPECT_LE(RotationFromDeg(w.own.T_cam_imu[cam], Basalt(cam)), 0.35) << "cam" << cam;
    EXPECT_LE(PositionFromM(w.own.T_cam_imu[cam], Basalt(cam)), 8e-3) << "cam" << cam;
  }
  EXPECT_NEAR(w.own.baseline_m, kPublishedBaselineM, 1e-3);
  EXPECT_LE(std::abs(w.own.baseline_m - kPublishedBaselineM), 3.0 * w.own.baseline_std_m);
  const std::vector<double> normalised = HalvesNormalisedDifferences("ds-none", chain);
  constexpr double kLimit[6] = {4.5, 3.0, 3.0, 3.0, 3.0, 3.0};
  for (size_t i = 0; i < normalised.size(); ++i) {
    EXPECT_LE(normalised[i], kLimit[i % 6]) << "cam" << i / 6 << " " << kComponentNames[i % 6];
  }
  std::printf("whole vs published: largest %.2f RMS %.2f; halves largest %.2f RMS %.2f\n",
              Largest(w.ratios), Rms(w.ratios), Largest(normalised), Rms(normalised));
  // As above: stds 4x too large would put the RMS below 0.25.
  EXPECT_GE(Rms(normalised), 0.25) << "reported standard deviations too large";
}

}  // namespace
}  // namespace splinecal
