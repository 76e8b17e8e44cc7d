// `splinecal detect` driven as a user runs it: the bundled EuRoC frame pair (data/, so this runs
// on a fresh clone), overlays, and every kind of bad input with its exit code and message.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "splinecal/io/observations_csv.h"
#include "splinecal/io/yaml_document.h"
#include "testing/run_tool.h"
#include "testing/strict_yaml.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;
namespace fs = std::filesystem;

const std::string kBundled = std::string(SPLINECAL_SOURCE_DIR) + "/data/euroc_april_frames";
const std::string kGrid = kBundled + "/aprilgrid.yaml";
const std::string kFrame = "1403709395937837056";

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

TEST(DetectCommand, FindsEveryCornerOfTheBundledStereoFrame) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  const testing::ToolResult r =
      testing::RunTool({"detect", "--images", kBundled + "/cam0," + kBundled + "/cam1",
                        "--target", kGrid, "--draw", "--out", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("detect: cam0 752 x 480: 1 of 1 images read, 1 with the target, "
                               "144 corners"));
  EXPECT_THAT(r.err, HasSubstr("2/2 frames"));  // the progress bar's last state
  const std::vector<Observation> observations = ReadObservationsCsv(out + "/observations.csv");
  ASSERT_EQ(observations.size(), 288u);
  for (const Observation& o : observations) EXPECT_EQ(o.t_ns, 1403709395937837056);
  EXPECT_EQ(observations.front().cam_id, 0);
  EXPECT_EQ(observations.back().cam_id, 1);

  EXPECT_EQ(testing::ExpectStrictYamlFilesIn(out), 1);
  const YamlDocument result(out + "/result.yaml");
  EXPECT_EQ(result.String("effort"), "default");  // the detector option that was used
  for (const std::string cam : {"cam0", "cam1"}) {
    EXPECT_EQ(result.Numbers("cameras/" + cam + "/resolution"), (std::vector<double>{752, 480}));
    EXPECT_EQ(result.Integer("cameras/" + cam + "/images_read"), 1);
    EXPECT_EQ(result.Integer("cameras/" + cam + "/images_with_target"), 1);
    EXPECT_EQ(result.Integer("cameras/" + cam + "/corners"), 144);
    EXPECT_GT(result.Number("cameras/" + cam + "/detection_time_s"), 0.0);
    EXPECT_TRUE(fs::exists(out + "/overlays/" + cam + "/" + kFrame + ".png"));
  }
}

TEST(DetectCommand, QuietPrintsNothing) {
  testing::TempDir dir;
  const testing::ToolResult r = testing::RunTool(
      {"detect", "--images", kBundled + "/cam0", "--target", kGrid, "--quiet", "--out",
       dir.File("out")});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_EQ(r.err, "");
}

// Exit 2, one line on stderr that contains `message`, and no file in `out`.
void ExpectRefused(const std::vector<std::string>& args, const std::string& out,
                   const std::string& message) {
  const testing::ToolResult r = testing::RunTool(args);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr(message));
  // --quiet is not given, so the progress may precede the error: the error is the last line.
  EXPECT_EQ(r.err.back(), '\n');
  EXPECT_FALSE(fs::exists(out + "/observations.csv"));
  EXPECT_FALSE(fs::exists(out + "/result.yaml"));
}

TEST(DetectCommand, RefusesFoldersWithNothingUsable) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  ExpectRefused({"detect", "--images", dir.File("absent"), "--target", kGrid, "--out", out}, out,
                "absent: no such folder");
  dir.Write("text/100.png", "not an image");
  dir.Write("text/200.png", ReadBytes(kBundled + "/cam0/data/" + kFrame + ".png").substr(0, 5000));
  ExpectRefused({"detect", "--images", dir.File("text"), "--target", kGrid, "--out", out}, out,
                "text: none of cam0's 2 images could be read (first problem: ");
  dir.Write("nofile/data.csv", "100,100.png\n");
  ExpectRefused({"detect", "--images", dir.File("nofile"), "--target", kGrid, "--out", out}, out,
                "nofile/data.csv: no image of data.csv exists under data/");
  // A readable image without the target.
  cv::Mat noise(480, 752, CV_8UC1);
  cv::randu(noise, 0, 255);
  fs::create_directories(dir.File("blank"));
  ASSERT_TRUE(cv::imwrite(dir.File("blank/100.png"), noise));
  ExpectRefused({"detect", "--images", dir.File("blank"), "--target", kGrid, "--out", out}, out,
                "this aprilgrid was found in none of the 1 images read; nothing was written");
  const std::string points = dir.Write("points.yaml",
                                       "target_type: points\npoints: [[0, 0, 0, 0], [1, 1, 0, 0], "
                                       "[2, 0, 1, 0], [3, 1, 1, 0]]\n");
  ExpectRefused({"detect", "--images", kBundled + "/cam0", "--target", points, "--out", out}, out,
                "detect finds aprilgrid and checkerboard targets, not 'points'");
  ExpectRefused({"detect", "--images", kBundled + "/cam0,", "--target", kGrid, "--out", out}, out,
                "--images: empty folder name");
  ExpectRefused({"detect", "--images", kBundled + "/cam0", "--target", kGrid, "--threads", "0",
                 "--out", out},
                out, "--threads: expected 1 to 256");
  ExpectRefused({"detect", "--images", kBundled + "/cam0", "--target", kGrid, "--effort", "slow",
                 "--out", out},
                out, "--effort: detect effort 'slow': expected fast, default or thorough");
}

// A target file that does not describe the printed board: the EuRoC frames show a 6 x 6 grid
// with tagSpacing 0.3. With 5, 7 or 8 tag columns most tags still pass the detector's neighbour
// check (neighbours in a row are neighbours in either numbering), so the corners would get wrong
// ids; the layout gate refuses them before anything is written, and names the 6 columns the
// decoded tags fit. A wrong tagSpacing is the layout check's own message. The right file passes
// (FindsEveryCornerOfTheBundledStereoFrame).
TEST(DetectCommand, RefusesATargetFileThatContradictsTheBoard) {
  testing::TempDir dir;
  const std::string out = dir.File("out");
  const std::string images = kBundled + "/cam0," + kBundled + "/cam1";
  for (const int cols : {5, 7, 8}) {
    const std::string grid = dir.Write(
        "grid" + std::to_string(cols) + ".yaml",
        "target_type: aprilgrid\ntagCols: " + std::to_string(cols) + "\ntagRows: " +
            std::to_string(cols) + "\ntagSize: 0.088\ntagSpacing: 0.3\n");
    ExpectRefused({"detect", "--images", images, "--target", grid, "--out", out}, out,
                  grid + ": the tags found in the images lie on an aprilgrid of 6 tag columns, "
                         "not the " + std::to_string(cols) + " of this file: set tagCols: 6");
  }
  const std::string spacing = dir.Write(
      "spacing.yaml",
      "target_type: aprilgrid\ntagCols: 6\ntagRows: 6\ntagSize: 0.088\ntagSpacing: 0.5\n");
  ExpectRefused({"detect", "--images", images, "--target", spacing, "--out", out}, out,
                "the images: the corners fit tagSpacing 0.30");
}

// Each effort finds the whole grid of the EuRoC frame (36 tags of ~40 px, found by the first
// search), at the same corners: the searches only add tags, the refinement is the same.
TEST(DetectCommand, EveryEffortFindsTheEurocGridAtTheSameCorners) {
  testing::TempDir dir;
  std::vector<std::vector<Observation>> found;
  for (const std::string effort : {"fast", "default", "thorough"}) {
    const std::string out = dir.File(effort);
    const testing::ToolResult r = testing::RunTool(
        {"detect", "--images", kBundled + "/cam0", "--target", kGrid, "--effort", effort,
         "--quiet", "--out", out});
    ASSERT_EQ(r.exit_code, 0) << r.err;
    found.push_back(ReadObservationsCsv(out + "/observations.csv"));
    ASSERT_EQ(found.back().size(), 144u) << effort;
    EXPECT_EQ(YamlDocument(out + "/result.yaml").String("effort"), effort);
  }
  for (size_t e = 1; e < found.size(); ++e) {
    for (size_t i = 0; i < found[0].size(); ++i) {
      EXPECT_EQ(found[e][i].point_id, found[0][i].point_id);
      EXPECT_EQ(found[e][i].uv, found[0][i].uv);
    }
  }
}

TEST(DetectCommand, ABadFrameIsAWarningAndTheRestIsProcessed) {
  testing::TempDir dir;
  const std::string good = ReadBytes(kBundled + "/cam0/data/" + kFrame + ".png");
  dir.Write("cam0/data.csv",
            "#timestamp [ns],filename\n50,tiny.png\n100,a.png\n200,b.png\n300,c.png\n");
  // A 1 x 1 image first (it must neither crash the tag detector nor decide the resolution).
  std::filesystem::create_directories(dir.File("cam0/data"));
  ASSERT_TRUE(cv::imwrite(dir.File("cam0/data/tiny.png"), cv::Mat(1, 1, CV_8UC1, cv::Scalar(0))));
  dir.Write("cam0/data/a.png", good);
  dir.Write("cam0/data/b.png", good.substr(0, good.size() - 100));  // truncated
  // c.png is missing
  const std::string out = dir.File("out");
  const testing::ToolResult r = testing::RunTool(
      {"detect", "--images", dir.File("cam0"), "--target", kGrid, "--out", out});
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.err, HasSubstr("warning: " + dir.File("cam0/data.csv") + ":5: image "));
  EXPECT_THAT(r.err, HasSubstr("b.png: truncated PNG (it ends before its IEND chunk) (" +
                               dir.File("cam0/data.csv") + ":4), frame skipped"));
  EXPECT_THAT(r.err, HasSubstr("tiny.png: 1 x 1 pixels, but cam0's frames are 752 x 480"));
  EXPECT_EQ(ReadObservationsCsv(out + "/observations.csv").size(), 144u);
  const YamlDocument result(out + "/result.yaml");
  EXPECT_EQ(result.Numbers("cameras/cam0/resolution"), (std::vector<double>{752, 480}));
  EXPECT_EQ(result.Integer("cameras/cam0/images_listed"), 3);  // c.png is not listed
  EXPECT_EQ(result.Integer("cameras/cam0/images_read"), 1);
  EXPECT_THAT(testing::ReadFileText(out + "/result.yaml"), HasSubstr("b.png: truncated PNG"));
}

}  // namespace
}  // namespace splinecal
