// `splinecal intrinsics` end to end on the bundled stereo chessboards (data/opencv_chessboard):
// detect, then intrinsics; the outputs read back (strict YAML, camchain.yaml through splinecal's
// own reader, unique HTML ids); bad input exits 2 with one line and writes nothing.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include <filesystem>
#include <string>
#include <vector>

#include "splinecal/io/camchain_yaml.h"
#include "testing/html_ids.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

const std::string kData = std::string(SPLINECAL_SOURCE_DIR) + "/data/opencv_chessboard";

// observations.csv of the bundled chessboards (detect run once per test binary).
const std::string& Observations() {
  static testing::TempDir* dir = new testing::TempDir;
  static const std::string path = [] {
    const testing::ToolResult detect = testing::RunTool({"detect",
                                                         "--images",
                                                         kData + "/cam0," + kData + "/cam1",
                                                         "--target",
                                                         kData + "/checkerboard.yaml",
                                                         "--quiet",
                                                         "--out",
                                                         dir->File("detect")});
    EXPECT_EQ(detect.exit_code, 0) << detect.err;
    return dir->File("detect") + "/observations.csv";
  }();
  return path;
}

std::vector<std::string> Args(const std::string& models, const std::string& out) {
  return {"intrinsics",
          "--observations",
          Observations(),
          "--target",
          kData + "/checkerboard.yaml",
          "--models",
          models,
          "--resolution",
          "640x480",
          "--out",
          out};
}

TEST(IntrinsicsCommand, StereoChessboardsGiveEveryOutput) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  const testing::ToolResult run = testing::RunTool(Args("pinhole-radtan,pinhole-radtan", out));
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 2);
  const YAML::Node result = testing::LoadStrictYamlFile(out + "/result.yaml");
  ASSERT_TRUE(result["cameras"].IsSequence());
  ASSERT_EQ(result["cameras"].size(), 2u);
  for (const YAML::Node& camera : result["cameras"]) {
    EXPECT_EQ(camera["camera_model"].as<std::string>(), "pinhole-radtan");
    EXPECT_EQ(camera["intrinsics"].size(), 4u);
    EXPECT_EQ(camera["intrinsics_std"].size(), 4u);
    EXPECT_EQ(camera["distortion_coeffs"].size(), 4u);
    EXPECT_EQ(camera["distortion_std"].size(), 4u);
    EXPECT_EQ(camera["views_used"].as<int>(), 13);
    EXPECT_LT(camera["reprojection_rms_px"].as<double>(), 0.3);
    for (size_t i = 0; i < 4; ++i) EXPECT_GT(camera["intrinsics_std"][i].as<double>(), 0.0);
  }
  EXPECT_FALSE(result["cameras"][0]["T_cn_cnm1"]);
  EXPECT_TRUE(result["cameras"][1]["T_cn_cnm1"].IsSequence());
  EXPECT_EQ(result["cameras"][1]["T_cn_cnm1_std"]["rotation_deg"].size(), 3u);

  // camchain.yaml reads back with the same values (17 significant digits).
  const Camchain camchain = ReadCamchainYaml(out + "/camchain.yaml");
  ASSERT_EQ(camchain.size(), 2u);
  EXPECT_EQ(camchain[0].camera.fu, result["cameras"][0]["intrinsics"][0].as<double>());
  EXPECT_EQ(camchain[1].camera.pv, result["cameras"][1]["intrinsics"][3].as<double>());
  EXPECT_EQ(camchain[0].camera.width, 640);
  // splinecal_covariance (docs/intrinsics.md): the active intrinsics in Kalibr's order, then for
  // cam1 T_cn_cnm1's tangent; a symmetric matrix whose diagonal gives result.yaml's stds.
  const YAML::Node chain = testing::LoadStrictYamlFile(out + "/camchain.yaml");
  const std::vector<std::string> names = {"fu", "fv", "pu", "pv", "k1", "k2", "p1", "p2"};
  for (int n = 0; n < 2; ++n) {
    const YAML::Node cov = chain["cam" + std::to_string(n)]["splinecal_covariance"];
    ASSERT_TRUE(cov.IsMap()) << "cam" << n;
    const auto parameters = cov["parameters"].as<std::vector<std::string>>();
    ASSERT_EQ(parameters.size(), n == 0 ? 8u : 14u);
    for (size_t i = 0; i < names.size(); ++i) EXPECT_EQ(parameters[i], names[i]);
    if (n == 1) {
      EXPECT_EQ(parameters[13], "T_cn_cnm1_phi_z");
    }
    const auto matrix = cov["matrix"].as<std::vector<std::vector<double>>>();
    ASSERT_EQ(matrix.size(), parameters.size());
    for (size_t i = 0; i < matrix.size(); ++i) {
      ASSERT_EQ(matrix[i].size(), parameters.size());
      for (size_t j = 0; j < i; ++j) EXPECT_NEAR(matrix[i][j], matrix[j][i], 1e-12 * matrix[i][i]);
    }
    const double std_fu = result["cameras"][n]["intrinsics_std"][0].as<double>();
    EXPECT_NEAR(std::sqrt(matrix[0][0]), std_fu, 1e-9 * std_fu);
    EXPECT_GT(cov["block_seconds"].as<double>(), 0.0);
  }

  const std::string report = testing::ReadFileText(out + "/report.html");
  EXPECT_THAT(report, HasSubstr("Errors and coverage by image position"));
  EXPECT_GE(testing::ExpectUniqueHtmlIds(report, "report.html"), 3);
}

struct BadCase {
  std::vector<std::string> change;  // flag, value pairs replacing the defaults
  std::string message;
};

TEST(IntrinsicsCommand, BadInputExitsTwoWithOneLineAndWritesNothing) {
  const std::vector<BadCase> cases = {
      {{"--models", "pinhole-radtann,pinhole-radtan"}, "unknown camera model 'pinhole-radtann'"},
      {{"--models", "pinhole-radtan"}, "cam_id 1"},
      {{"--resolution", "640by480"}, "is not WIDTHxHEIGHT"},
      {{"--resolution", "640x480,640x480,640x480"}, "3 sizes for 2 models"},
      {{"--min-corners", "3"}, "at least 6"},
      {{"--max-views", "-1"}, "--max-views"},
  };
  for (const BadCase& c : cases) {
    SCOPED_TRACE(c.message);
    testing::TempDir dir;
    const std::string out = dir.File("out");
    std::vector<std::string> args = Args("pinhole-radtan,pinhole-radtan", out);
    for (size_t i = 0; i < c.change.size(); i += 2) {
      auto it = std::find(args.begin(), args.end(), c.change[i]);
      if (it != args.end()) {
        *(it + 1) = c.change[i + 1];
      } else {
        args.push_back(c.change[i]);
        args.push_back(c.change[i + 1]);
      }
    }
    const testing::ToolResult run = testing::RunTool(args);
    EXPECT_EQ(run.exit_code, 2);
    EXPECT_EQ(testing::CountLines(run.err), 1) << run.err;
    EXPECT_THAT(run.err, HasSubstr(c.message));
    EXPECT_FALSE(std::filesystem::exists(out + "/result.yaml"));
  }
}

TEST(IntrinsicsCommand, NeedsExactlyOneSourceOfTheImageSize) {
  testing::TempDir dir;
  std::vector<std::string> args = Args("pinhole-radtan,pinhole-radtan", dir.File("out"));
  args.erase(std::find(args.begin(), args.end(), "--resolution"),
             std::find(args.begin(), args.end(), "--resolution") + 2);
  const testing::ToolResult run = testing::RunTool(args);
  EXPECT_EQ(run.exit_code, 2);
  EXPECT_THAT(run.err, HasSubstr("give --resolution or --camchain"));
}

}  // namespace
}  // namespace splinecal
