// What the tests of generated text (report pages, figures, console summaries) check most: that the
// text contains each of a list of fragments.
#ifndef SPLINECAL_TESTS_TESTING_TEXT_CHECKS_H_
#define SPLINECAL_TESTS_TESTING_TEXT_CHECKS_H_

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <initializer_list>
#include <string>

namespace splinecal {
namespace testing {

// EXPECT_THAT(text, HasSubstr(fragment)) for each fragment: a failure shows the fragment missing.
inline void ExpectContainsEach(const std::string& text,
                               std::initializer_list<std::string> fragments) {
  for (const std::string& fragment : fragments) EXPECT_THAT(text, ::testing::HasSubstr(fragment));
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_TEXT_CHECKS_H_
