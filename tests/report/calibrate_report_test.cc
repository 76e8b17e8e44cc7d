#include "splinecal/report/calibrate_report.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <regex>
#include <set>
#include <string>
#include <vector>

#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"
#include "splinecal/report/reprojection_figures.h"
#include "testing/html_ids.h"
#include "testing/strict_yaml.h"
#include "testing/text_checks.h"

namespace splinecal {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

CameraEstimate Camera(double shift_s) {
  CameraEstimate e;
  e.calibration.camera.width = 752;
  e.calibration.camera.height = 480;
  e.calibration.T_cam_imu =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.1, -0.2, 0.3)), Eigen::Vector3d(0.01, 0.02, -0.03));
  e.calibration.time_offset_s = shift_s;
  e.calibration.line_delay_s = 2e-5;
  e.rotation_std_deg = Eigen::Vector3d(0.01, 0.02, 0.03);
  e.translation_std_m = Eigen::Vector3d(1e-3, 2e-3, 3e-3);
  e.time_offset_std_s = 1e-4;
  e.time_offset_estimated = true;
  e.reprojection_rms_px = 0.4;
  e.num_frames = 12;
  e.num_observations = 340;
  return e;
}

// A small result with `num_cameras` cameras, residuals and a 6-pose spline of 0.1 s knots.
CalibrationResult SmallResult(int num_cameras) {
  CalibrationResult r;
  for (int c = 0; c < num_cameras; ++c) r.cameras.push_back(Camera(1e-3 * (c + 1)));
  r.layout.t0_ns = 1'000'000'000;
  r.layout.dt_ns = 100'000'000;
  r.layout.num_control_poses = 6;
  for (int i = 0; i < 6; ++i) {
    r.control_poses.push_back(SE3d(SO3d::Exp(Eigen::Vector3d(0.0, 0.0, 0.1 * i)),
                                   Eigen::Vector3d(0.2 * i, 0.1 * i, 1.0)));
  }
  r.gyro_bias = Eigen::Vector3d(1e-3, -2e-3, 3e-3);
  r.accel_bias = Eigen::Vector3d(0.01, 0.02, -0.03);
  r.gravity_w = Eigen::Vector3d(0.0, 0.0, -9.81);
  r.pixel_sigma_px = 0.5;
  r.pixel_sigma_estimated = true;
  r.warnings = {"the time offset is weakly determined", "a <tagged> warning"};
  for (int k = 0; k < 50; ++k) {
    const int64_t t_ns = r.layout.t0_ns + 150'000'000 + k * 5'000'000;
    r.reprojection_samples.push_back(
        {t_ns, k % num_cameras, k, Eigen::Vector2d(100.0 + k, 200.0), Eigen::Vector2d(0.1, -0.2)});
    ImuResidualRecord imu;
    imu.t_ns = t_ns;
    imu.gyro_error = Eigen::Vector3d::Constant(1e-4);
    r.imu_samples.push_back(imu);
  }
  return r;
}

const CalibrateReportInputs kInputs = {
    "imu0.csv", "observations.csv", "camchain.yaml", "aprilgrid.yaml", "", "imu <adis>.yaml"};

std::string Report(const CalibrationResult& r) {
  return CalibrateReportHtml(r, CalibrateOptions(), kInputs);
}

// The keys at column 0 of a YAML document.
std::set<std::string> TopLevelKeys(const std::string& yaml) {
  std::set<std::string> keys;
  const std::regex key("^([A-Za-z_0-9]+):", std::regex::multiline);
  for (auto it = std::sregex_iterator(yaml.begin(), yaml.end(), key); it != std::sregex_iterator();
       ++it) {
    keys.insert((*it)[1]);
  }
  return keys;
}

TEST(CalibrateResultYaml, EveryKeyOnceAndCam0AtTheTop) {
  for (int num_cameras : {1, 2}) {
    const CalibrationResult r = SmallResult(num_cameras);
    const std::string text = CalibrateResultYaml(r, CalibrateOptions());
    // A strict parser refuses a repeated key (cam0's reprojection_rms_px and the pooled one were
    // once both written as reprojection_rms_px).
    EXPECT_THAT(testing::DuplicateYamlKeys(text), ::testing::IsEmpty()) << text;
  }
  const CalibrationResult r = SmallResult(1);
  const std::string text = CalibrateResultYaml(r, CalibrateOptions());
  const std::set<std::string> unique = TopLevelKeys(text);
  for (const char* expected : {"T_cam_imu",
                               "rotation_std_deg",
                               "translation_std_m",
                               "timeshift_cam_imu",
                               "timeshift_estimated",
                               "timeshift_std_s",
                               "line_delay",
                               "line_delay_estimated",
                               "line_delay_std",
                               "reprojection_rms_px",
                               "reprojection_rms_px_all_cameras",
                               "num_frames",
                               "num_observations",
                               "gyro_bias",
                               "gyro_bias_std",
                               "accel_bias",
                               "accel_bias_std",
                               "gravity_w",
                               "pixel_sigma_px",
                               "pixel_sigma_estimated",
                               "gyro_rms",
                               "accel_rms",
                               "num_imu_samples",
                               "num_landmarks",
                               "knot_spacing_s",
                               "trajectory",
                               "bias_model",
                               "rolling_shutter",
                               "huber_px",
                               "iterations",
                               "rounds",
                               "initialisation_time_s",
                               "solve_time_s",
                               "covariance_time_s",
                               "covariance_ok",
                               "termination",
                               "warnings"}) {
    EXPECT_EQ(unique.count(expected), 1u) << expected;
  }
  EXPECT_EQ(unique.count("cameras"), 0u);  // one camera: no per-camera map
  const YAML::Node yaml = testing::LoadStrictYaml(text);
  EXPECT_DOUBLE_EQ(yaml["timeshift_cam_imu"].as<double>(), 1e-3);
  EXPECT_DOUBLE_EQ(yaml["knot_spacing_s"].as<double>(), 0.1);
  EXPECT_EQ(yaml["bias_model"].as<std::string>(), "spline");
  EXPECT_EQ(yaml["trajectory"].as<std::string>(), "se3");
  EXPECT_EQ(yaml["warnings"].size(), 2u);
  EXPECT_EQ(yaml["T_cam_imu"].size(), 4u);
}

TEST(CalibrateResultYaml, SeveralCamerasUnderCameras) {
  const YAML::Node yaml =
      testing::LoadStrictYaml(CalibrateResultYaml(SmallResult(2), CalibrateOptions()));
  ASSERT_TRUE(yaml["cameras"]);
  EXPECT_DOUBLE_EQ(yaml["cameras"]["cam1"]["timeshift_cam_imu"].as<double>(), 2e-3);
  EXPECT_DOUBLE_EQ(yaml["timeshift_cam_imu"].as<double>(), 1e-3);  // cam0 at the top
}

TEST(CalibrateReprojectionCsv, HeaderAndOneRowPerSample) {
  const CalibrationResult r = SmallResult(2);
  const std::string csv = CalibrateReprojectionCsv(r);
  EXPECT_THAT(csv,
              StartsWith("#t_ns,cam_id,point_id,u,v,error_u,error_v\n1150000000,0,0,100,200,"));
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 50);
}

TEST(CalibrateReportHtml, EverySectionAndTheEstimates) {
  const std::string html = Report(SmallResult(2));
  EXPECT_THAT(html, StartsWith("<!DOCTYPE html>"));
  testing::ExpectContainsEach(html,
                              {"<title>splinecal calibrate</title>",
                               "<tr><th colspan=3>cam0</th></tr>",
                               "<tr><th colspan=3>cam1</th></tr>",
                               "<tr><th>timeshift_cam_imu [ms]</th><td>2.0000</td>",
                               "<tr><th>T_cam_imu translation [mm]</th><td>10.00, 20.00, -30.00",
                               "0.500 (estimated)",
                               "<h2>Warnings</h2>",
                               "<h2>Reprojection</h2>",
                               "<h2>Reprojection by image position</h2>",
                               "<h2>IMU</h2>",
                               "<h2>IMU biases</h2>",
                               "<h2>Trajectory</h2>",
                               "<li>a &lt;tagged&gt; warning</li>"});
  EXPECT_THAT(html, Not(HasSubstr("<tagged>")));
  EXPECT_THAT(html, EndsWith("</body></html>\n"));
}

TEST(CalibrateReportHtml, NoWarningsNoWarningSection) {
  CalibrationResult r = SmallResult(1);
  r.warnings.clear();
  EXPECT_THAT(Report(r), Not(HasSubstr("Warnings")));
}

TEST(CalibrateSummaryText, CamerasResidualsAndWarnings) {
  const std::string text = CalibrateSummaryText(SmallResult(2));
  EXPECT_THAT(text, StartsWith("cam0 T_cam_imu:\n  ["));
  testing::ExpectContainsEach(text,
                              {"cam1 T_cam_imu:\n",
                               "  timeshift_cam_imu 2.000000 ms (std 0.1000 ms)\n",
                               "  line_delay 20.0000 us/row (fixed)\n",
                               "  reprojection RMS 0.400 px over 340 points in 12 frames\n",
                               "pixel sigma 0.500 px (estimated)\n"});
  EXPECT_THAT(text, EndsWith("warning: a <tagged> warning\n"));
}

TEST(CalibrateReportHtml, IdsAreUniqueAcrossItsInlinedSvgs) {
  // Every figure defines a clip path per panel; with the same ids in each inlined SVG a browser
  // clipped the IMU residuals (72 s of data) to the rectangle of an earlier, narrower panel.
  const std::string html = Report(SmallResult(2));
  EXPECT_GE(testing::ExpectUniqueHtmlIds(html, "report.html"), 10);
  EXPECT_THAT(html, Not(HasSubstr("<?xml")));  // no XML declaration inside HTML
}

TEST(CalibrateReportHtml, ListsTheInputsAndTheNoiseModel) {
  const std::string html = Report(SmallResult(1));
  EXPECT_THAT(html,
              HasSubstr("<p>IMU: imu0.csv<br>observations: observations.csv<br>camchain: "
                        "camchain.yaml<br>target: aprilgrid.yaml</p>"));
  EXPECT_THAT(html, Not(HasSubstr("initial poses:")));  // not given
  EXPECT_THAT(html, HasSubstr("given: imu &lt;adis&gt;.yaml</caption>"));
  EXPECT_THAT(html, HasSubstr("<td>gyroscope_noise_density</td><td>0.00016968</td>"));
  EXPECT_THAT(html, HasSubstr("<td>accelerometer_random_walk</td><td>0.003</td>"));
  EXPECT_THAT(html, HasSubstr("bias spline, knots every 0.1 s, Huber 2 px"));
  EXPECT_THAT(html, HasSubstr(", trajectory se3</td>"));
}

TEST(CalibrateReportHtml, BiasesOverTimeWhenTheResultCarriesThem) {
  CalibrationResult r = SmallResult(1);
  const std::string means_only = Report(r);
  EXPECT_THAT(means_only, HasSubstr("IMU biases (means only)"));
  EXPECT_THAT(means_only, HasSubstr("carries the biases' time averages only"));
  for (size_t k = 0; k < r.imu_samples.size(); ++k) {
    r.imu_samples[k].gyro_bias = r.gyro_bias + Eigen::Vector3d::Constant(1e-5 * k);
    r.imu_samples[k].accel_bias = r.accel_bias - Eigen::Vector3d::Constant(1e-4 * k);
  }
  const std::string course = Report(r);
  EXPECT_THAT(course, HasSubstr("IMU biases over time"));
  EXPECT_THAT(course, Not(HasSubstr("means only")));
}

TEST(ReprojectionErrorFigure, OneColourPerCamera) {
  const plot::Figure figure = ReprojectionErrorFigure(ReprojectionDataOf(SmallResult(2)), 6000);
  ASSERT_EQ(figure.panels.size(), 2u);
  for (const plot::Panel& panel : figure.panels) {
    ASSERT_EQ(panel.series.size(), 2u);
    for (int cam = 0; cam < 2; ++cam) {
      EXPECT_EQ(panel.series[cam].label, "cam" + std::to_string(cam));
      EXPECT_EQ(panel.series[cam].color, CameraColor(cam));
      EXPECT_EQ(panel.series[cam].x.size(), 25u);  // SmallResult alternates the cameras
    }
  }
  EXPECT_NE(CameraColor(0), CameraColor(1));
}

// Corners on a 20 px lattice over cam0's 752 x 480 image, each with a small alternating error,
// plus `bias` [px] on every corner left of u = 100 and above v = 100 (a model mismatch there).
CalibrationResult LatticeResult(const Eigen::Vector2d& bias) {
  CalibrationResult r = SmallResult(1);
  r.reprojection_samples.clear();
  int k = 0;
  for (int v = 5; v < 480; v += 20) {
    for (int u = 5; u < 752; u += 20) {
      for (int repeat = 0; repeat < 4; ++repeat, ++k) {
        ReprojectionSample s;
        s.uv = Eigen::Vector2d(u, v);
        s.error = Eigen::Vector2d(k % 2 == 0 ? 0.2 : -0.2, 0.0);
        if (u < 100 && v < 100) s.error += bias;
        r.reprojection_samples.push_back(s);
      }
    }
  }
  return r;
}

TEST(MakeReprojectionImageFigure, ARegionWithAMismatchStandsOut) {
  const ReprojectionImageFigure map = MakeReprojectionImageFigure(
      ReprojectionDataOf(LatticeResult(Eigen::Vector2d(3.0, 0.0))), 100000);
  ASSERT_EQ(map.figure.panels.size(), 1u);
  const plot::Panel& panel = map.figure.panels[0];
  // The image with a margin of 4% of its width (its outline shows).
  EXPECT_NEAR(panel.x.max, 752.0 * 1.04, 1e-9);
  EXPECT_NEAR(panel.y.max, 480.0 + 752.0 * 0.04, 1e-9);
  EXPECT_TRUE(panel.y.reversed);  // v down, as the image shows it
  // Classes < 0.5, 0.5-1, 1-2, 2-5, >= 5 px, then the cell vectors, their dots, their
  // arrowheads and the image's outline.
  ASSERT_EQ(panel.series.size(), 9u);
  const size_t mismatched = 4 * 5 * 5;              // 5 x 5 lattice points in the corner, 4 each
  EXPECT_EQ(panel.series[3].x.size(), mismatched);  // |error| = 2.8 or 3.2 px
  EXPECT_EQ(panel.series[0].x.size() + panel.series[3].x.size(),
            LatticeResult({0, 0}).reprojection_samples.size());
  // A cell is 752 / 12 = 62.7 px: the corner's mean error of 3 px takes the gain 0.8 * 62.7 / 3
  // = 16.7 down to 10; elsewhere the alternating errors average to 0.
  EXPECT_EQ(map.vector_gain, 10.0);
  const plot::Series& vectors = panel.series[5];
  double longest = 0.0;
  for (size_t i = 0; i + 1 < vectors.x.size(); i += 3) {
    longest = std::max(
        longest, std::hypot(vectors.x[i + 1] - vectors.x[i], vectors.y[i + 1] - vectors.y[i]));
  }
  EXPECT_NEAR(longest, 30.0, 1e-9);
  EXPECT_THAT(map.key_html, HasSubstr("magnified x10"));
  EXPECT_THAT(map.key_html, HasSubstr("&#9679;</span> &lt; 0.5 px,"));  // escaped for HTML
}

TEST(MakeReprojectionImageFigure, NoiseAloneGivesShortVectors) {
  const ReprojectionImageFigure map = MakeReprojectionImageFigure(
      ReprojectionDataOf(LatticeResult(Eigen::Vector2d::Zero())), 100000);
  const plot::Panel& panel = map.figure.panels[0];
  EXPECT_EQ(panel.series[0].x.size(), LatticeResult({0, 0}).reprojection_samples.size());
  for (int k = 1; k < 5; ++k) EXPECT_TRUE(panel.series[k].x.empty()) << k;
}

namespace splinecal {
namespace {

// cam0's intrinsics estimated with a prior (fu moved by 2 px), cam1's held; the target scale
// checked; the command line given.
CalibrationResult WithIntrinsicsAndScale(CalibrateOptions* options) {
  CalibrationResult r = SmallResult(2);
  CameraEstimate& e = r.cameras[0];
  e.calibration.camera.fu = 460.0;
  e.calibration.camera.fv = 455.0;
  e.intrinsics_before = e.calibration.camera.intrinsics();
  e.intrinsics_before(0) = 458.0;
  e.intrinsics_mode = ParameterMode::kPrior;
  e.intrinsics_estimated = true;
  for (int i = 0; i < 4; ++i) {
    e.intrinsics_prior_std(i) = 1.0 + i;
    e.intrinsics_std(i) = 0.5 + i;
  }
  r.cameras[1].intrinsics_before = r.cameras[1].calibration.camera.intrinsics();
  r.camera_chain = ParameterMode::kPrior;
  r.target_scale_mode = TargetScaleMode::kCheck;
  r.target_scale = 1.0042;
  r.target_scale_std = 0.0031;
  options->command_line = "splinecal calibrate --imu <imu>.csv --intrinsics prior";
  return r;
}

TEST(CalibrateResultYaml, IntrinsicsBeforeAfterPriorAndRun) {
  CalibrateOptions options;
  const CalibrationResult r = WithIntrinsicsAndScale(&options);
  const std::string text = CalibrateResultYaml(r, options);
  EXPECT_THAT(testing::DuplicateYamlKeys(text), ::testing::IsEmpty()) << text;
  const YAML::Node yaml = testing::LoadStrictYaml(text);
  EXPECT_EQ(yaml["intrinsics_mode"].as<std::string>(), "prior");
  EXPECT_EQ(yaml["intrinsics"][0].as<double>(), 460.0);
  EXPECT_EQ(yaml["intrinsics_before"][0].as<double>(), 458.0);
  EXPECT_EQ(yaml["intrinsics_prior_std"][1].as<double>(), 2.0);
  EXPECT_EQ(yaml["intrinsics_std"][3].as<double>(), 3.5);
  EXPECT_EQ(yaml["cameras"]["cam1"]["intrinsics_mode"].as<std::string>(), "held");
  EXPECT_FALSE(yaml["cameras"]["cam1"]["intrinsics_std"]);  // held: no std
  EXPECT_FALSE(yaml["cameras"]["cam1"]["intrinsics_prior_std"]);
  EXPECT_EQ(yaml["camera_chain"].as<std::string>(), "prior");
  EXPECT_EQ(yaml["target_scale_mode"].as<std::string>(), "check");
  EXPECT_EQ(yaml["target_scale"].as<double>(), 1.0042);
  EXPECT_EQ(yaml["target_scale_std"].as<double>(), 0.0031);
  EXPECT_EQ(yaml["target_scale_used"].as<double>(), 1.0);
  EXPECT_EQ(yaml["command_line"].as<std::string>(),
            "splinecal calibrate --imu <imu>.csv --intrinsics prior");
}

TEST(CalibrateReportHtml, RunAndIntrinsicsSections) {
  CalibrateOptions options;
  const CalibrationResult r = WithIntrinsicsAndScale(&options);
  const std::string html = CalibrateReportHtml(r, options, kInputs);
  EXPECT_THAT(html, HasSubstr("<h2>Run</h2>\n<p><code>splinecal calibrate --imu &lt;imu&gt;.csv "
                              "--intrinsics prior</code></p>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>intrinsics</th><td>cam0 prior, cam1 held</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>camera chain (T_cn_cnm1)</th><td>prior</td></tr>"));
  EXPECT_THAT(html, HasSubstr("check: 1.0042 (std 0.0031) against the IMU, then held at 1"));
  EXPECT_THAT(html, HasSubstr("<h2>Intrinsics</h2>"));
  // fu: 458 (prior std 1) -> 460 (std 0.5): +2.00 prior stds; cam1's entries are held.
  EXPECT_THAT(html, HasSubstr("<tr><th>fu</th><td>458.0000 (1)</td><td>460.0000 (0.5)</td>"
                              "<td>+2.00</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<td>held</td></tr>"));
  EXPECT_THAT(CalibrateSummaryText(r), HasSubstr("target scale against the IMU 1.0042 (std "
                                                 "0.0031), held at 1\n"));
  EXPECT_THAT(CalibrateSummaryText(r), HasSubstr("  intrinsics prior\n"));
}

}  // namespace
}  // namespace splinecal

// A scale-misalignment(-size-effect) estimate: every matrix with its std, one entry held (NaN
// std with a covariance: calibrate held it at nominal).
CalibrationResult ResultWithImuModel(ImuModelKind kind) {
  CalibrationResult r = SmallResult(1);
  r.covariance_ok = true;
  r.imu_model.model = kind;
  ImuIntrinsicsd& p = r.imu_model.intrinsics;
  p.M_a << 1.0011, 0, 0, -0.0052, 0.9987, 0, 0.003, 0.0017, 0.9943;
  p.M_g << 1.0048, 0, 0, -0.0007, 1.0044, 0, 0.0047, 0.0013, 0.9979;
  p.A << 2.6e-4, 0, 0, 0, -1.1e-4, 0, 0, 0, 5e-5;
  p.C_gyro_i = SO3d::Exp(Eigen::Vector3d(0.001, -0.002, -0.0074)).matrix();
  p.ry_i = Eigen::Vector3d(0.0012, -0.0005, 0.0003);
  p.rz_i = Eigen::Vector3d(-0.0004, 0.0009, 0.0021);
  ImuModelStd& s = r.imu_model_std;
  s.M_a << 0.0021, NAN, NAN, 0.0029, 0.002, NAN, 0.0035, 0.0033, 0.0031;
  s.M_g << 0.0011, NAN, NAN, 0.00066, 0.0011, NAN, 0.00058, 0.00065, 0.00023;
  s.A = Eigen::Matrix3d::Constant(4e-5);
  s.A(2, 1) = NAN;  // held
  s.C_gyro_i_deg = Eigen::Vector3d(0.1673, 0.169, 0.1425);
  s.ry_i = Eigen::Vector3d(6.3e-4, 6e-4, 1.07e-3);
  s.rz_i = Eigen::Vector3d(8.5e-4, 4.8e-4, 2.14e-3);
  return r;
}

TEST(CalibrateSummaryText, TheImuModelEachEntryWithItsStd) {
  const std::string text =
      CalibrateSummaryText(ResultWithImuModel(ImuModelKind::kScaleMisalignmentSizeEffect));
  EXPECT_THAT(text,
              HasSubstr("IMU model scale-misalignment-size-effect (Kalibr's imu0; each entry: "
                        "value (std))\n"));
  // M's upper triangle is no parameter: its zeros carry no std.
  EXPECT_THAT(text, HasSubstr("  M_a row 0: 1.001100 (0.002100), 0, 0\n"));
  EXPECT_THAT(text, HasSubstr("  M_a row 2: 0.003000 (0.003500), 0.001700 (0.003300), "
                              "0.994300 (0.003100)\n"));
  EXPECT_THAT(text, HasSubstr("  M_g row 1: -0.000700 (0.000660), 1.004400 (0.001100), 0\n"));
  EXPECT_THAT(text, HasSubstr("  A [(rad/s)/(m/s^2)] row 2: 0.000e+00 (4.000e-05), "
                              "0.000e+00 (held), 5.000e-05 (4.000e-05)\n"));
  EXPECT_THAT(text, HasSubstr("  C_gyro_i rotation vector [deg]: 0.0573 (0.1673), -0.1146 (0.1690), "
                              "-0.4240 (0.1425)\n"));
  EXPECT_THAT(text, HasSubstr("  ry_i [mm]: 1.200 (0.630), -0.500 (0.600), 0.300 (1.070)\n"));
  EXPECT_THAT(text, HasSubstr("  rz_i [mm]: -0.400 (0.850), 0.900 (0.480), 2.100 (2.140)\n"));
  // Without the size effect no lever arms; without a covariance no std is "held".
  CalibrationResult sm = ResultWithImuModel(ImuModelKind::kScaleMisalignment);
  sm.covariance_ok = false;
  const std::string sm_text = CalibrateSummaryText(sm);
  EXPECT_THAT(sm_text, HasSubstr("IMU model scale-misalignment (Kalibr's imu0"));
  EXPECT_THAT(sm_text, Not(HasSubstr("ry_i")));
  EXPECT_THAT(sm_text, HasSubstr("0.000e+00 (no std)"));
  // The calibrated model has no section.
  EXPECT_THAT(CalibrateSummaryText(SmallResult(1)), Not(HasSubstr("IMU model")));
}

TEST(CalibrateReportHtml, TheImuModelEachEntryWithItsStd) {
  const std::string html = Report(ResultWithImuModel(ImuModelKind::kScaleMisalignmentSizeEffect));
  EXPECT_THAT(html, HasSubstr("<h2>IMU model</h2>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>M_a row 1</th><td>-0.005200, 0.998700, 0</td>"
                              "<td>std 0.002900, 0.002000, -</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>M_g row 2</th><td>0.004700, 0.001300, 0.997900</td>"
                              "<td>std 0.000580, 0.000650, 0.000230</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>A [(rad/s)/(m/s^2)] row 0</th><td>2.600e-04, 0.000e+00, 0.000e+00"));
  EXPECT_THAT(html, HasSubstr("<tr><th>C_gyro_i rotation vector [deg]</th><td>0.0573, -0.1146, "
                              "-0.4240</td><td>std 0.1673, 0.1690, 0.1425</td></tr>"));
  EXPECT_THAT(html, HasSubstr("<tr><th>rz_i [mm]</th><td>-0.400, 0.900, 2.100</td>"
                              "<td>std 0.850, 0.480, 2.140</td></tr>"));
  EXPECT_THAT(Report(SmallResult(1)), Not(HasSubstr("<h2>IMU model</h2>")));
}

}  // namespace
}  // namespace splinecal
