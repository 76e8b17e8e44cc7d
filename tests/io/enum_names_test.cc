#include "splinecal/enum_names.h"

#include <gtest/gtest.h>

#include <array>

namespace splinecal {
namespace {

// Tables with rows wider than EnumName (RowOf and a third member): imu/imu_model_kind.cc, tested
// in tests/imu/imu_model_kind_test.cc.
enum class Colour { kRed, kGreen, kBlue };

constexpr std::array<EnumName<Colour>, 3> kColourNames = {{
    {Colour::kRed, "red"},
    {Colour::kGreen, "green"},
    {Colour::kBlue, "blue"},
}};

TEST(EnumNames, NameAndParseReadTheSameTable) {
  for (const EnumName<Colour>& row : kColourNames) {
    EXPECT_STREQ(NameOf(kColourNames, row.value), row.name);
    Colour parsed = row.value == Colour::kRed ? Colour::kBlue : Colour::kRed;
    ASSERT_TRUE(ValueNamed(kColourNames, row.name, &parsed)) << row.name;
    EXPECT_EQ(parsed, row.value) << row.name;
  }
}

TEST(EnumNames, OtherTextIsNoValueAndLeavesTheOutputAlone) {
  // Exact spelling only: no case folding, no prefix, no surrounding space.
  for (const char* text : {"Red", "re", "red ", "", "green,blue"}) {
    Colour parsed = Colour::kGreen;
    EXPECT_FALSE(ValueNamed(kColourNames, text, &parsed)) << "'" << text << "'";
    EXPECT_EQ(parsed, Colour::kGreen) << "'" << text << "'";
  }
}

TEST(EnumNames, JoinsEveryNameInTableOrder) {
  EXPECT_EQ(JoinNames(kColourNames, ", "), "red, green, blue");
  EXPECT_EQ(JoinNames(kColourNames, "|"), "red|green|blue");
}

}  // namespace
}  // namespace splinecal
