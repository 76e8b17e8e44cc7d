#include <sstream>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/imu/imu_model.h"
#include "splinecal/io/spline_csv.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using testing::CountLines;
using ::testing::HasSubstr;
using testing::ReadFileText;
using testing::RefusedInOneLine;
using testing::RunTool;
using testing::TempDir;

// Control poses on the one-parameter subgroup T_i = Exp(i dt xi): the spline moves with the
// constant body twist xi, so the predicted gyro is exactly omega + b_g everywhere.
std::string SubgroupSplineCsv(const Vector6<double>& xi, double dt_s) {
  std::vector<SE3d> poses;
  for (int i = 0; i < 8; ++i) poses.push_back(SE3d::Exp(xi * (i * dt_s)));
  std::ostringstream text;
  WriteSplineCsv(SE3Splined(poses, 1000000000, static_cast<int64_t>(dt_s * 1e9)), &text);
  return text.str();
}

TEST(EvaluateCommand, PrintsAndWritesThePredictedImu) {
  TempDir dir;
  Vector6<double> xi;
  xi << 1.0, 0.0, 0.0, 0.0, 0.0, 0.5;  // forward at 1 m/s while turning at 0.5 rad/s
  const std::string spline = dir.Write("spline.csv", SubgroupSplineCsv(xi, 0.1));
  const auto result = RunTool({"evaluate", "--spline", spline, "--out", dir.File("out"),
                               "--samples", "3", "--every", "0.01", "--gyro-bias", "0.1,0,0"});
  ASSERT_EQ(result.exit_code, 0) << result.err;
  EXPECT_THAT(result.out, HasSubstr("8 control poses"));
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(dir.File("out")), 1);
  const std::string csv = ReadFileText(dir.File("out/evaluation.csv"));
  EXPECT_EQ(CountLines(csv), 1 + 51);  // header + 0.5 s of valid range at 100 Hz, ends included
  const std::string samples = ReadFileText(dir.File("out/samples.csv"));
  std::istringstream lines(samples);
  std::string line;
  std::getline(lines, line);  // header
  int rows = 0;
  while (std::getline(lines, line)) {
    std::vector<double> v;
    std::stringstream fields(line);
    std::string field;
    while (std::getline(fields, field, ',')) v.push_back(std::stod(field));
    ASSERT_EQ(v.size(), 23u);
    EXPECT_NEAR(v[17], 0.1, 1e-12);  // gyro x = 0 + b_g
    EXPECT_NEAR(v[19], 0.5, 1e-12);  // gyro z = omega_z
    ++rows;
  }
  EXPECT_EQ(rows, 3);
  EXPECT_THAT(ReadFileText(dir.File("out/result.yaml")), HasSubstr("num_control_poses: 8"));
}

// A step longer than the valid range gives its first row alone (it once became a 1 ns step).
TEST(EvaluateCommand, EveryLongerThanTheRangeWritesOneRow) {
  TempDir dir;
  Vector6<double> xi;
  xi << 1.0, 0.0, 0.0, 0.0, 0.0, 0.5;
  const std::string spline = dir.Write("spline.csv", SubgroupSplineCsv(xi, 0.1));
  for (const char* every : {"0.6", "1e300"}) {
    const auto result = RunTool(
        {"evaluate", "--spline", spline, "--out", dir.File("out"), "--every", every, "--quiet"});
    ASSERT_EQ(result.exit_code, 0) << result.err;
    EXPECT_EQ(CountLines(ReadFileText(dir.File("out/evaluation.csv"))), 1 + 1) << every;
  }
}

TEST(EvaluateCommand, BadInputIsOneLineExitTwoAndNoOutput) {
  TempDir dir;
  const std::string bad = dir.Write("bad.csv", "0,0,0,0,1,0,0,0\n10,0,0,0,1,0,0,0\n");
  const auto result = RunTool({"evaluate", "--spline", bad, "--out", dir.File("out")});
  EXPECT_TRUE(RefusedInOneLine(result, "bad.csv: a spline needs at least 4 control poses"));
  EXPECT_FALSE(std::ifstream(dir.File("out/result.yaml")));

  const auto unknown = RunTool({"evaluate", "--splin", bad});
  EXPECT_EQ(unknown.exit_code, 2);
  EXPECT_THAT(unknown.err, HasSubstr("unknown flag '--splin'"));
  const auto bad_value = RunTool({"evaluate", "--samples", "many"});
  EXPECT_EQ(bad_value.exit_code, 2);
  EXPECT_THAT(bad_value.err, HasSubstr("--samples: 'many' is not a valid int32"));
  const auto missing_value = RunTool({"evaluate", "--spline"});
  EXPECT_EQ(missing_value.exit_code, 2);
  EXPECT_THAT(missing_value.err, HasSubstr("needs a value"));
  const auto bias =
      RunTool({"evaluate", "--spline", bad, "--out", dir.File("o"), "--gyro-bias", "1,2"});
  EXPECT_EQ(bias.exit_code, 2);
}

// The model line of spline.csv: evaluate follows it (result.yaml and the table say which) and
// refuses an unknown model in one line, exit code 2, writing nothing.
TEST(EvaluateCommand, FollowsTheTrajectoryLineAndRefusesAnUnknownModel) {
  TempDir dir;
  Vector6<double> xi;
  xi << 1.0, 0.0, 0.0, 0.0, 0.0, 0.5;
  std::string text = SubgroupSplineCsv(xi, 0.1);
  ASSERT_EQ(text.rfind("# trajectory: se3\n", 0), 0u);
  text = text.substr(text.find('\n') + 1);
  const auto split = RunTool({"evaluate",
                              "--spline",
                              dir.Write("split.csv", "# trajectory: split\n" + text),
                              "--out",
                              dir.File("split")});
  ASSERT_EQ(split.exit_code, 0) << split.err;
  EXPECT_THAT(split.out, HasSubstr(", split, valid"));
  EXPECT_THAT(ReadFileText(dir.File("split/result.yaml")), HasSubstr("trajectory: \"split\""));

  const std::string bad = dir.Write("bad.csv", "# trajectory: kalibr\n" + text);
  const auto result = RunTool({"evaluate", "--spline", bad, "--out", dir.File("out")});
  EXPECT_TRUE(
      RefusedInOneLine(result, "bad.csv:1: trajectory: expected se3 or split, got 'kalibr'"));
  EXPECT_FALSE(std::ifstream(dir.File("out/result.yaml")));
}

}  // namespace
}  // namespace splinecal
