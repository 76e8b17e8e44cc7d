// Every file of the fuzz seed corpora and every input a fuzzer once found (tests/fuzz/) goes
// through every reader: each must return or throw splinecal::Error, nothing else.
#include <filesystem>

#include <gtest/gtest.h>

#include "splinecal/error.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/yaml_document.h"

namespace splinecal {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> CorpusFiles() {
  std::vector<std::string> files;
  const fs::path root = fs::path(SPLINECAL_SOURCE_DIR) / "tests" / "fuzz";
  for (const char* sub : {"corpus", "regressions"}) {
    if (!fs::exists(root / sub)) continue;
    for (const auto& entry : fs::recursive_directory_iterator(root / sub)) {
      if (entry.is_regular_file()) files.push_back(entry.path().string());
    }
  }
  std::sort(files.begin(), files.end());
  return files;
}

template <typename Reader>
void ExpectReturnsOrThrowsError(const std::string& path, Reader reader) {
  try {
    reader(path);
  } catch (const Error&) {
  } catch (const std::exception& e) {
    ADD_FAILURE() << path << ": threw " << e.what();
  }
}

TEST(FuzzCorpus, EveryReaderReturnsOrThrowsError) {
  const auto files = CorpusFiles();
  ASSERT_FALSE(files.empty());
  for (const std::string& path : files) {
    ExpectReturnsOrThrowsError(path, [](const std::string& p) { ReadEurocImu(p); });
    ExpectReturnsOrThrowsError(path, [](const std::string& p) { ReadEurocGroundTruth(p); });
    ExpectReturnsOrThrowsError(path, [](const std::string& p) { ReadPoses(p); });
    ExpectReturnsOrThrowsError(path, [](const std::string& p) { ReadImuYaml(p); });
    ExpectReturnsOrThrowsError(path, [](const std::string& p) {
      const YamlDocument yaml(p);
      yaml.Rows("cam0/T_cam_imu");
    });
  }
}

}  // namespace
}  // namespace splinecal
