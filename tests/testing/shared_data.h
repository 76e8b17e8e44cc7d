// Real data for the tests lives beside the repository in ../shared/data (README.md, "Real data").
// A fresh clone on a user's machine may not have it: a test that needs it then skips, saying so.
// Under CI (CI=true) a missing file is a failure instead, so that a missing data set can never
// pass CI as a silent skip.
#ifndef SPLINECAL_TESTS_TESTING_SHARED_DATA_H_
#define SPLINECAL_TESTS_TESTING_SHARED_DATA_H_

#include <gtest/gtest.h>

#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

#include "testing/paths.h"

namespace splinecal {
namespace testing {

// The path of `relative` below ../shared/data (e.g. "euroc_v1_01_easy/imu0.csv").
inline std::string SharedDataPath(const std::string& relative) {
  return testing::SharedDataDir() + "/" + relative;
}

inline bool RunningUnderCi() {
  const char* ci = std::getenv("CI");
  return ci != nullptr && std::strcmp(ci, "true") == 0;
}

}  // namespace testing
}  // namespace splinecal

// Ends the test when the shared file or folder `relative` is absent: a skip on a developer's
// machine, a failure under CI. Use at the top of a TEST body.
#define SPLINECAL_REQUIRE_SHARED_DATA(relative)                                               \
  do {                                                                                        \
    const std::string splinecal_shared_path = ::splinecal::testing::SharedDataPath(relative); \
    if (!std::filesystem::exists(splinecal_shared_path)) {                                    \
      if (::splinecal::testing::RunningUnderCi()) {                                           \
        FAIL() << "shared data absent under CI: " << splinecal_shared_path;                   \
      }                                                                                       \
      GTEST_SKIP() << "shared data absent: " << splinecal_shared_path;                        \
    }                                                                                         \
  } while (false)

#endif  // SPLINECAL_TESTS_TESTING_SHARED_DATA_H_
