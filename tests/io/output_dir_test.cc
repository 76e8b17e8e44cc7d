#include "splinecal/io/output_dir.h"

#include <filesystem>

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/io/yaml_writer.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using testing::ReadFileText;
using testing::TempDir;
namespace fs = std::filesystem;

int EntriesIn(const std::string& dir) {
  int count = 0;
  for (auto it = fs::recursive_directory_iterator(dir); it != fs::recursive_directory_iterator();
       ++it) {
    ++count;
  }
  return count;
}

TEST(OutputDir, NothingAppearsWithoutCommit) {
  TempDir dir;
  const std::string out = dir.File("results");
  {
    OutputDir output(out);
    output.WriteFile("result.yaml", "a: 1\n");
    output.WriteFile("mav0/imu0/data.csv", "x\n");
  }
  EXPECT_EQ(EntriesIn(out), 0);
}

TEST(OutputDir, CommitMovesEverythingIntoPlaceAndKeepsOldFilesUntilThen) {
  TempDir dir;
  const std::string out = dir.File("results");
  dir.Write("results/result.yaml", "old\n");
  {
    OutputDir output(out);
    output.WriteFile("result.yaml", "new\n");
    output.WriteFile("mav0/imu0/data.csv", "x\n");
    EXPECT_EQ(ReadFileText(out + "/result.yaml"), "old\n");
    output.Commit();
  }
  EXPECT_EQ(ReadFileText(out + "/result.yaml"), "new\n");
  EXPECT_EQ(ReadFileText(out + "/mav0/imu0/data.csv"), "x\n");
  EXPECT_EQ(EntriesIn(out), 4);  // result.yaml, mav0, mav0/imu0, data.csv: no staging left
}

TEST(OutputDir, RefusesAFileInTheWayAndEscapingNames) {
  TempDir dir;
  const std::string file = dir.Write("file", "x");
  EXPECT_THROW(OutputDir output(file), Error);
  OutputDir output(dir.File("ok"));
  EXPECT_THROW(output.WriteFile("../escape", "x"), Error);
  EXPECT_THROW(output.WriteFile("/abs", "x"), Error);
}

TEST(YamlWriter, NestedMapsVectorsMatricesAndExactNumbers) {
  YamlWriter yaml;
  yaml.Scalar("success", true);
  yaml.Scalar("message", "a \"quoted\" word");
  yaml.BeginMap("gyroscope");
  yaml.Scalar("noise_density", 1.0 / 3.0);
  yaml.Vector("bias", Eigen::Vector3d(1, -2, std::nan("")));
  yaml.EndMap();
  yaml.Matrix("T", Eigen::Matrix2d::Identity());
  yaml.StringList("warnings", {});
  EXPECT_EQ(yaml.str(),
            "success: true\n"
            "message: \"a \\\"quoted\\\" word\"\n"
            "gyroscope:\n"
            "  noise_density: 0.33333333333333331\n"
            "  bias: [1, -2, .nan]\n"
            "T:\n"
            "  - [1, 0]\n"
            "  - [0, 1]\n"
            "warnings: []\n");
}

}  // namespace
}  // namespace splinecal
