// What the tests of bad input check: the message of the splinecal::Error a call throws, and each
// bad file of a table refused with a message that names the file and the problem
// (docs/conventions.md: bad input is one Error naming the file, line and problem).
#ifndef SPLINECAL_TESTS_TESTING_REFUSALS_H_
#define SPLINECAL_TESTS_TESTING_REFUSALS_H_

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "splinecal/error.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

// The message of the Error that `f` throws, "no error" when it throws none (HasSubstr of the
// expected message then fails and shows it).
template <typename F>
std::string ErrorOf(const F& f) {
  try {
    f();
  } catch (const Error& e) {
    return e.what();
  }
  return "no error";
}

// Each case's text written to `file_name` in a fresh folder and given to `read` (a reader taking
// the path): refused with a message that contains the case's message and the file's name.
template <typename Read>
void ExpectEachFileRefused(const std::vector<std::pair<std::string, std::string>>& cases,
                           const std::string& file_name,
                           const Read& read) {
  TempDir dir;
  for (const auto& [text, message] : cases) {
    const std::string path = dir.Write(file_name, text);
    const std::string error = ErrorOf([&] { read(path); });
    EXPECT_THAT(error, ::testing::HasSubstr(message)) << text;
    EXPECT_THAT(error, ::testing::HasSubstr(file_name)) << text;
  }
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_REFUSALS_H_
