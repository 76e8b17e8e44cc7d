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
#include "testing/run_tool.h"
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
  const std::string report = testing::ReadFileText(out + "/report.html");
  EXPECT_THAT(report, HasSubstr("<svg"));
  EXPECT_THAT(report, HasSubstr("Reprojection errors"));
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
  // A corrupt observation row.
  const std::string bad = dir_.Write("bad.csv", "#t_ns,cam_id,point_id,u,v\n1,0,2,3\n");
  std::vector<std::string> args = Args(out);
  args[4] = bad;
  testing::ToolResult r = testing::RunTool(args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_EQ(testing::CountLines(r.err), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("bad.csv:2"));
  EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml"));
  // A missing camchain.
  args = Args(out);
  args[6] = dir_.File("missing.yaml");
  r = testing::RunTool(args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("missing.yaml"));
  // The target never seen.
  args = Args(out);
  args[8] = dir_.Write("points.yaml",
                       "target_type: points\npoints:\n  - [9000, 0, 0, 0]\n"
                       "  - [9001, 1, 0, 0]\n  - [9002, 0, 1, 0]\n  - [9003, 1, 1, 0]\n");
  r = testing::RunTool(args);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("never seen"));
  EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml"));
}

}  // namespace
}  // namespace splinecal
