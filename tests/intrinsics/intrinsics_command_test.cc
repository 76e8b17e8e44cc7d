// `splinecal intrinsics` end to end on the bundled stereo chessboards (data/opencv_chessboard):
// detect, then intrinsics; the outputs read back (strict YAML, camchain.yaml through splinecal's
// own reader, unique HTML ids); bad input exits 2 with one line and writes nothing. And
// --target-deformation on simulated views of an AprilGrid printed off its file: result.yaml's
// target_deformation block (and view_inset.csv) holds what the library call gives on the same
// files.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "intrinsics/intrinsics_simulation.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/camera_specs.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/target_yaml.h"
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
      {{"--target-deformation", "bowed"},
       "--target-deformation: expected none, quadratic, cubic, in-plane, in-plane-per-view, "
       "points, points-in-plane, got 'bowed'"},
      // The checkerboard has no tags: in plane is refused before the solve, naming the file.
      {{"--target-deformation", "in-plane"},
       "checkerboard.yaml: target deformation in-plane: needs an aprilgrid"},
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

// The kind's block of result.yaml against the library's result on the same files: every
// coefficient and its std, and the derived in-plane quantities (report/intrinsics_report.h).
void ExpectDeformationBlock(const YAML::Node& block, const TargetDeformationResult& d) {
  const auto near = [](double value, double expected) {
    return std::abs(value - expected) <= 1e-9 * std::max(std::abs(expected), 1e-12);
  };
  ASSERT_TRUE(block.IsMap());
  EXPECT_EQ(block["kind"].as<std::string>(), TargetDeformationName(d.shape.kind));
  const YAML::Node coefficients = block["coefficients"];
  ASSERT_EQ(coefficients.size(), static_cast<size_t>(d.coefficients.size()));
  const std::vector<std::string> names = TargetDeformationCoefficientNames(d.shape.kind);
  for (int k = 0; k < d.coefficients.size(); ++k) {
    EXPECT_EQ(coefficients[k]["name"].as<std::string>(), names[k]);
    EXPECT_EQ(coefficients[k]["unit"].as<std::string>(), "ratio");
    EXPECT_PRED2(near, coefficients[k]["value"].as<double>(), d.coefficients(k));
    EXPECT_PRED2(near, coefficients[k]["std"].as<double>(), std::sqrt(d.covariance(k, k)));
  }
  // The tag side with the file's 88 mm and its pitch held: 88 (1 + d), d at the insets' mean
  // per view; Kalibr's tagSpacing for the file's tagSize: 1.3 / (1 + d) - 1.
  double inset = 0.0;
  if (d.shape.per_view_inset()) {
    for (const auto& [t_ns, d_v] : d.view_inset) inset += d_v / d.view_inset.size();
  } else {
    inset = d.coefficients(TargetShape::kInsetColumn);
  }
  std::map<std::string, YAML::Node> derived;
  for (const YAML::Node& q : block["derived"]) derived[q["name"].as<std::string>()] = q;
  ASSERT_EQ(derived.size(), 4u);
  EXPECT_PRED2(near, derived["x_over_y_scale"]["value"].as<double>(), 1 + 2 * d.coefficients(0));
  EXPECT_PRED2(near, derived["tag_size_mm"]["value"].as<double>(), 88.0 * (1.0 + inset));
  EXPECT_DOUBLE_EQ(derived["tag_size_mm"]["file"].as<double>(), 88.0);
  EXPECT_PRED2(near, derived["tag_spacing"]["value"].as<double>(), 1.3 / (1.0 + inset) - 1.0);
}

// 40 views of an AprilGrid printed off its file (e1 0.2%, e2 -0.15%, d 1%) by EuRoC's cam0,
// drawn with `seed` into dir/observations.csv; returns its path.
std::string WriteOffLayoutViews(const testing::TempDir& dir, int seed) {
  testing::IntrinsicsScene scene;
  scene.cameras = {testing::EurocCam0()};
  scene.T_cn_c0 = {SE3d()};
  scene.views = 40;
  scene.shape_kind = TargetDeformationKind::kInPlane;
  scene.shape[0] = 2e-3;
  scene.shape[1] = -1.5e-3;
  scene.shape[2] = 1e-2;
  const std::string observations = dir.File("observations.csv");
  std::ofstream csv(observations);
  WriteObservationsCsv(testing::SimulateIntrinsicsViews(scene, seed), &csv);
  return observations;
}

TEST(IntrinsicsCommand, TargetDeformationWritesTheLibrarysEstimate) {
  testing::TempDir dir;
  const std::string observations = WriteOffLayoutViews(dir, 7);
  const std::string target = std::string(SPLINECAL_SOURCE_DIR) + "/data/calibration/aprilgrid.yaml";
  for (TargetDeformationKind kind :
       {TargetDeformationKind::kInPlane, TargetDeformationKind::kInPlanePerView}) {
    const std::string name = TargetDeformationName(kind);
    SCOPED_TRACE(name);
    const std::string out = dir.File(name);
    const testing::ToolResult run = testing::RunTool({"intrinsics",
                                                      "--observations",
                                                      observations,
                                                      "--target",
                                                      target,
                                                      "--models",
                                                      "pinhole-radtan",
                                                      "--resolution",
                                                      "752x480",
                                                      "--target-deformation",
                                                      name,
                                                      "--threads",
                                                      "1",
                                                      "--out",
                                                      out});
    ASSERT_EQ(run.exit_code, 0) << run.err;
    EXPECT_THAT(run.err, HasSubstr("target deformation " + name + ": e1 "));

    // The library on the same files, as the command calls it.
    std::vector<Observation> points = ReadObservationsCsv(observations);
    const std::vector<IntrinsicsCameraSpec> specs =
        IntrinsicsCameraSpecs("pinhole-radtan", "752x480", "", "", &points);
    IntrinsicsOptions options;
    options.solver.num_threads = 1;
    options.target_deformation = kind;
    const IntrinsicsResult expected =
        CalibrateIntrinsics(points, ReadTargetYaml(target), specs, options);
    const TargetDeformationResult& d = expected.target_deformation;

    EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 2);
    const YAML::Node result = testing::LoadStrictYamlFile(out + "/result.yaml");
    EXPECT_DOUBLE_EQ(result["cameras"][0]["reprojection_rms_px"].as<double>(),
                     expected.cameras[0].reprojection_rms_px);
    ExpectDeformationBlock(result["target_deformation"], d);
    EXPECT_THAT(testing::ReadFileText(out + "/report.html"),
                HasSubstr("Target deformation: " + name));
    if (kind == TargetDeformationKind::kInPlane) {
      EXPECT_FALSE(std::filesystem::exists(out + "/view_inset.csv"));
      continue;
    }
    // Per view: the count in result.yaml, each timestamp's d_v in view_inset.csv.
    EXPECT_EQ(result["target_deformation"]["view_inset"]["count"].as<size_t>(),
              d.view_inset.size());
    std::istringstream csv(testing::ReadFileText(out + "/view_inset.csv"));
    std::string line;
    std::getline(csv, line);
    EXPECT_EQ(line, "#t_ns,d");
    size_t rows = 0;
    for (const auto& [t_ns, d_v] : d.view_inset) {
      ASSERT_TRUE(std::getline(csv, line));
      const size_t comma = line.find(',');
      EXPECT_EQ(std::stoll(line.substr(0, comma)), t_ns);
      EXPECT_DOUBLE_EQ(std::stod(line.substr(comma + 1)), d_v);
      ++rows;
    }
    EXPECT_EQ(rows, 40u);
    EXPECT_FALSE(std::getline(csv, line));
  }
}

// Every point free: target.yaml is the library's refined target, readable as a target file
// (calibrate's --target), and target_points.csv has a row per point.
TEST(IntrinsicsCommand, TargetPointsWritesTheRefinedTarget) {
  testing::TempDir dir;
  const std::string observations = WriteOffLayoutViews(dir, 8);
  const std::string target = std::string(SPLINECAL_SOURCE_DIR) + "/data/calibration/aprilgrid.yaml";
  const std::string out = dir.File("points");
  const testing::ToolResult run = testing::RunTool(
      {"intrinsics", "--observations", observations, "--target", target, "--models",
       "pinhole-radtan", "--resolution", "752x480", "--target-deformation", "points",
       "--threads", "1", "--out", out});
  ASSERT_EQ(run.exit_code, 0) << run.err;
  EXPECT_THAT(run.err, HasSubstr("target deformation points:"));
  std::vector<Observation> points = ReadObservationsCsv(observations);
  const std::vector<IntrinsicsCameraSpec> specs =
      IntrinsicsCameraSpecs("pinhole-radtan", "752x480", "", "", &points);
  IntrinsicsOptions options;
  options.solver.num_threads = 1;
  options.target_deformation = TargetDeformationKind::kPoints;
  const IntrinsicsResult expected =
      CalibrateIntrinsics(points, ReadTargetYaml(target), specs, options);
  const CalibrationTarget& refined = expected.target_deformation.refined_target;
  ASSERT_EQ(refined.points.size(), 144u);
  const CalibrationTarget written = ReadTargetYaml(out + "/target.yaml");
  EXPECT_EQ(written.type, "points");
  ASSERT_EQ(written.points.size(), refined.points.size());
  for (const auto& [id, p] : refined.points) {
    EXPECT_LT((written.points.at(id) - p).norm(), 1e-12) << "point " << id;
  }
  const YAML::Node result = testing::LoadStrictYamlFile(out + "/result.yaml");
  EXPECT_EQ(result["target_deformation"]["kind"].as<std::string>(), "points");
  EXPECT_EQ(result["target_deformation"]["refined_target"].as<std::string>(), "target.yaml");
  EXPECT_THAT(testing::ReadFileText(out + "/report.html"), HasSubstr("Target points"));
  std::istringstream csv(testing::ReadFileText(out + "/target_points.csv"));
  std::string line;
  size_t rows = 0;
  while (std::getline(csv, line)) ++rows;
  EXPECT_EQ(rows, 145u);  // the header and every point
}

}  // namespace
}  // namespace splinecal
