// `splinecal calibrate` driven as a user runs it (tests/testing/run_tool.h). Skipped until the
// command is registered in src/cli/commands.cc.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "calib/calibrate_test_scenario.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/observations_csv.h"
#include "testing/html_ids.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

class CalibrateCommand : public ::testing::Test {
 protected:
  void SetUp() override {
    testing::ScenarioOptions o;
    o.duration_s = 5.0;
    const testing::CalibrationScenario s = testing::MakeCalibrationScenario(o);
    std::ostringstream imu;
    WriteEurocImu(s.imu, &imu);
    imu_ = dir_.Write("imu0/data.csv", imu.str());
    std::ostringstream obs;
    WriteObservationsCsv(s.observations, &obs);
    observations_ = dir_.Write("observations.csv", obs.str());
    camchain_ = dir_.Write("camchain.yaml", "%YAML:1.0\n" + CamchainYamlText(s.start));
    target_ = dir_.Write("april.yaml",
                         "target_type: 'aprilgrid'\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\n"
                         "tagSpacing: 0.3\n");
  }

  std::vector<std::string> Args(const std::string& out) {
    return {"calibrate",
            "--imu",
            imu_,
            "--observations",
            observations_,
            "--camchain",
            camchain_,
            "--target",
            target_,
            "--rolling-shutter",
            "--threads",
            "2",
            "--out",
            out};
  }

  testing::TempDir dir_;
  std::string imu_, observations_, camchain_, target_;
};

TEST_F(CalibrateCommand, WritesKalibrCamchainResultAndReport) {
  const std::string out = dir_.File("out");
  const testing::ToolResult r = testing::RunTool(Args(out));
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("T_cam_imu"));
  EXPECT_THAT(r.err, HasSubstr("calibrate: round 1 iteration"));
  const Camchain estimated = ReadCamchainYaml(out + "/camchain-imucam.yaml");
  ASSERT_EQ(estimated.size(), 1u);
  EXPECT_GT(estimated[0].line_delay_s, 2e-5);
  const std::string result = testing::ReadFileText(out + "/result.yaml");
  for (const char* key : {"T_cam_imu:",
                          "rotation_std_deg:",
                          "translation_std_m:",
                          "timeshift_cam_imu:",
                          "timeshift_std_s:",
                          "line_delay:",
                          "line_delay_std:",
                          "gyro_bias:",
                          "accel_bias:",
                          "reprojection_rms_px:",
                          "gyro_rms:",
                          "accel_rms:",
                          "warnings:"}) {
    EXPECT_THAT(result, HasSubstr(key));
  }
  // Every key once (a strict YAML parser refuses repeats): camchain-imucam.yaml, result.yaml.
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 2);
  // One camera: no T_cn_cnm1 (Kalibr writes it from cam1 on).
  EXPECT_FALSE(testing::LoadStrictYamlFile(out + "/camchain-imucam.yaml")["cam0"]["T_cn_cnm1"]);
  const std::string report = testing::ReadFileText(out + "/report.html");
  EXPECT_THAT(report, HasSubstr("<svg"));
  EXPECT_THAT(report, HasSubstr("Reprojection errors"));
  EXPECT_THAT(report, HasSubstr("Reprojection errors by image position"));
  EXPECT_THAT(report, HasSubstr("IMU biases"));
  EXPECT_THAT(report, HasSubstr("<p>IMU: " + imu_));
  EXPECT_THAT(report, HasSubstr("<caption>IMU noise model: ADIS16448 defaults"));
  // Unique ids: the SVGs' clip paths once shared ids, which clipped later plots to earlier
  // panels (the IMU residuals stopped at 35 s of a 72 s recording).
  // A clip path per panel: reprojection 2, by image position 1, IMU 2, biases 2, trajectory 2.
  EXPECT_EQ(testing::ExpectUniqueHtmlIds(report, "report.html"), 9);
  EXPECT_TRUE(std::filesystem::exists(out + "/spline.csv"));
  EXPECT_TRUE(std::filesystem::exists(out + "/reprojection_errors.csv"));
}

TEST_F(CalibrateCommand, QuietSilencesProgress) {
  std::vector<std::string> args = Args(dir_.File("quiet"));
  args.push_back("--quiet");
  const testing::ToolResult r = testing::RunTool(args);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

TEST_F(CalibrateCommand, BadInputExitsTwoWithOneLineAndNoOutput) {
  const std::string out = dir_.File("bad");
  // Args(out) with argument `index` replaced by `value` must fail with exit code 2 and one line
  // holding `message`, and write nothing (--quiet: no progress lines before the error).
  auto expect_refused = [&](size_t index, const std::string& value, const std::string& message) {
    std::vector<std::string> args = Args(out);
    args[index] = value;
    args.push_back("--quiet");
    const testing::ToolResult r = testing::RunTool(args);
    EXPECT_EQ(r.exit_code, 2) << message;
    EXPECT_EQ(testing::CountLines(r.err), 1) << r.err;
    EXPECT_THAT(r.err, HasSubstr(message));
    EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml")) << message;
  };
  // A corrupt observation row.
  expect_refused(4, dir_.Write("bad.csv", "#t_ns,cam_id,point_id,u,v\n1,0,2,3\n"), "bad.csv:2");
  // A missing camchain.
  expect_refused(6, dir_.File("missing.yaml"), "missing.yaml");
  // Kalibr's imu.yaml given as --imu (Kalibr's own name for its noise file): named as YAML, with
  // the flag it belongs to.
  const std::string imu_yaml = dir_.Write("imu.yaml",
                                          "#Accelerometers\naccelerometer_noise_density: 1.86e-03\n"
                                          "accelerometer_random_walk: 4.33e-04\nrostopic: /imu0\n");
  expect_refused(2, imu_yaml, "imu.yaml:2: a YAML file ('accelerometer_noise_density: 1.86e-03')");
  expect_refused(2, imu_yaml, "go to --imu-yaml; --imu takes the IMU samples");
  // The target never seen.
  expect_refused(8,
                 dir_.Write("points.yaml",
                            "target_type: points\npoints:\n  - [9000, 0, 0, 0]\n"
                            "  - [9001, 1, 0, 0]\n  - [9002, 0, 1, 0]\n  - [9003, 1, 1, 0]\n"),
                 "never seen");
}

}  // namespace
}  // namespace splinecal
