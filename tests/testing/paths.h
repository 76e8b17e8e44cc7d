// Where the tests find the command-line tool, the source tree (data/, tests/fuzz/) and the shared
// real data (../shared/data). The paths are absolute and differ from one checkout to the next, so
// they are compiled into one generated file (tests/testing/paths.cc.in, configured by
// tests/CMakeLists.txt) instead of being passed to every test file on its command line: a fresh
// clone in another folder then recompiles that one file, and every other test object hits the
// compiler cache (CCACHE_BASEDIR in CMakeLists.txt makes the rest of the command line relative).
#ifndef SPLINECAL_TESTS_TESTING_PATHS_H_
#define SPLINECAL_TESTS_TESTING_PATHS_H_

#include <string>

namespace splinecal {
namespace testing {

// The splinecal binary the command-line tests run.
std::string ToolPath();

// The repository's root folder (the bundled data is SourceDir() + "/data").
std::string SourceDir();

// ../shared/data, or the folder given with -DSPLINECAL_SHARED_DATA_DIR=...
std::string SharedDataDir();

// The path of `relative` below the bundled data folder data/ (always present in a checkout).
inline std::string BundledDataPath(const std::string& relative) {
  return SourceDir() + "/data/" + relative;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_PATHS_H_
