#include "splinecal/string_printf.h"

#include <cstdint>
#include <cstdlib>
#include <string>

#include <gtest/gtest.h>

namespace splinecal {
namespace {

TEST(StringPrintf, FormatsLikePrintf) {
  EXPECT_EQ(StringPrintf("%d %s %.3g", 42, "rad/s", 0.000123456), "42 rad/s 0.000123");
  EXPECT_EQ(StringPrintf("%.0f%%", 12.5), "12%");
  EXPECT_EQ(StringPrintf("no arguments"), "no arguments");
  EXPECT_EQ(StringPrintf("%s", ""), "");
}

// The implementation switches from a stack buffer to a second pass for long results: check
// both sides of that switch and far beyond, so that nothing is ever cut.
TEST(StringPrintf, NeverTruncates) {
  for (const size_t length : {0, 1, 255, 511, 512, 513, 1000, 100000}) {
    const std::string text(length, 'x');
    const std::string result = StringPrintf("<%s>", text.c_str());
    ASSERT_EQ(result.size(), length + 2) << length;
    EXPECT_EQ(result, "<" + text + ">");
  }
}

TEST(FormatDouble, SeventeenDigitsReadBackExactly) {
  EXPECT_EQ(FormatDouble(0.1), "0.10000000000000001");
  EXPECT_EQ(FormatDouble(-2.5), "-2.5");
  EXPECT_EQ(FormatDouble(1e300), "1.0000000000000001e+300");
  for (const double value : {0.1, 1.0 / 3.0, -9.80665, 1.2345678901234567e-200, 6.02214076e23}) {
    EXPECT_EQ(std::strtod(FormatDouble(value).c_str(), nullptr), value);
  }
}

}  // namespace
}  // namespace splinecal
