#include "splinecal/io/number_parser.h"

#include <gtest/gtest.h>

#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "splinecal/io/detail/number_parser_avx2.h"

namespace splinecal {
namespace internal {
namespace {

// The fields are read right-aligned: put the field after bytes of the kinds that precede fields in
// a file (digits, points, signs, commas), so that those bytes must be masked off.
class Field {
 public:
  explicit Field(const std::string& text, uint32_t salt = 0) {
    for (int i = 0; i < 48; ++i) buffer_[i] = "0123456789.-,e+ "[(salt * 7 + i * 13) % 16];
    std::memcpy(buffer_ + 48, text.data(), text.size());
    buffer_[48 + text.size()] = ',';
    begin_ = buffer_ + 48;
    end_ = begin_ + text.size();
  }
  bool Decimal(double* value) const { return ParseDecimalField(begin_, end_, value); }
#if defined(SPLINECAL_HAS_AVX2_PARSER)
  // The AVX2 reader, its digits rounded in the first of four lanes (the others filled with
  // `neighbour`'s digits, as a row's other fields would be): false when it leaves the field to
  // from_chars. Only where CpuHasAvx2Parser().
  bool DecimalAvx2(const DecimalDigits& neighbour, double* value) const {
    DecimalDigits digits[4] = {neighbour, neighbour, neighbour, neighbour};
    if (!ReadDecimalFieldAvx2(begin_, end_, &digits[0])) return false;
    double rounded[4];
    if ((RoundDecimals4(digits, rounded) & 1) == 0) {
      *value = rounded[0];
      return true;
    }
    return DecimalToDouble(
        digits[0].w, -static_cast<int>(digits[0].fraction_digits), digits[0].negative, value);
  }
#endif
  bool Integer(int64_t* value) const { return ParseInt64Field(begin_, end_, value); }
  // What std::from_chars reads when it reads the whole field.
  bool FromChars(double* value) const {
    const std::from_chars_result result = std::from_chars(begin_, end_, *value);
    return result.ec == std::errc() && result.ptr == end_;
  }
  bool FromChars(int64_t* value) const {
    const std::from_chars_result result = std::from_chars(begin_, end_, *value);
    return result.ec == std::errc() && result.ptr == end_;
  }

 private:
  char buffer_[128] = {};
  const char* begin_;
  const char* end_;
};

uint64_t Bits(double x) {
  uint64_t bits;
  std::memcpy(&bits, &x, 8);
  return bits;
}

// Whether the scalar reader and, where the CPU has it, the AVX2 reader read `text` themselves
// (true) or leave it to from_chars (false): both must answer `read`.
void ExpectReadsDecimal(const char* text, bool read) {
  double value = 0.0;
  EXPECT_EQ(Field(text).Decimal(&value), read) << text;
#if defined(SPLINECAL_HAS_AVX2_PARSER)
  if (CpuHasAvx2Parser()) {
    EXPECT_EQ(Field(text).DecimalAvx2(DecimalDigits(), &value), read) << text;
  }
#endif
}

// True when the field is refused, or read exactly as std::from_chars reads it.
::testing::AssertionResult SameAsFromChars(const std::string& text, uint32_t salt = 0) {
  const Field field(text, salt);
  double fast = 0.0;
  if (field.Decimal(&fast)) {
    double reference = 0.0;
    if (!field.FromChars(&reference) || Bits(fast) != Bits(reference)) {
      return ::testing::AssertionFailure() << "'" << text << "' read as " << fast;
    }
  }
#if defined(SPLINECAL_HAS_AVX2_PARSER)
  DecimalDigits neighbour;
  neighbour.w = 1234567890123456789u;
  neighbour.fraction_digits = salt % 20;
  double fast_avx2 = 0.0;
  if (CpuHasAvx2Parser() && field.DecimalAvx2(neighbour, &fast_avx2)) {
    double reference = 0.0;
    if (!field.FromChars(&reference) || Bits(fast_avx2) != Bits(reference)) {
      return ::testing::AssertionFailure() << "'" << text << "' read as " << fast_avx2 << " (AVX2)";
    }
  }
#endif
  int64_t fast_integer = 0;
  if (field.Integer(&fast_integer)) {
    int64_t reference = 0;
    if (!field.FromChars(&reference) || fast_integer != reference) {
      return ::testing::AssertionFailure() << "'" << text << "' read as " << fast_integer;
    }
  }
  return ::testing::AssertionSuccess();
}

TEST(NumberParser, ReadsTheCommonFieldsAsFromChars) {
  for (const char* text : {"0.014257895137467579",
                           "-0.019841528145679438",
                           "0.0053339482360438865",
                           "9.843849070129261",
                           "9.365351",
                           "-0.335061",
                           "0.0",
                           "-0.0",
                           "00.5",
                           "1234567.5",
                           "0.1",
                           "0.3",
                           "-3.277056",
                           "9007199254740992.5",
                           "0.000000000000000000000000000001"}) {
    ExpectReadsDecimal(text, true);
    EXPECT_TRUE(SameAsFromChars(text));
  }
  for (const char* text : {"1403636579758555392", "0", "007", "9223372036854775807"}) {
    int64_t value = 0;
    EXPECT_TRUE(Field(text).Integer(&value)) << text;
    EXPECT_TRUE(SameAsFromChars(text));
  }
}

TEST(NumberParser, LeavesEverythingElseToFromChars) {
  for (const char* text : {"1e-05",
                           "1.5E3",
                           "+1.5",
                           ".5",
                           "5.",
                           "5",
                           "inf",
                           "nan",
                           "-inf",
                           "1.2.3",
                           "--1.0",
                           "-",
                           "1 .5",
                           "1.5 ",
                           "0x1.8p1",
                           "1,5",
                           "",
                           "12345678901234567890.5",             // 21 significant digits
                           "0.12345678901234567890",             // 20
                           "0.0000000000000000000000000000001",  // 33 characters
                           "9007199254740993.0"}) {              // exactly halfway: a tie
    ExpectReadsDecimal(text, false);
  }
  for (const char* text :
       {"-5", "+5", "9223372036854775808", "12a", "1.0", "", "12345678901234567890"}) {
    int64_t value = 0;
    EXPECT_FALSE(Field(text).Integer(&value)) << text;
  }
}

// Random fields of the shapes a file holds, and decimals next to the halfway point between two
// doubles (where the rounding is hardest): every field read is what std::from_chars reads.
TEST(NumberParser, RandomFieldsReadAsFromChars) {
  std::mt19937_64 rng(16);
  int read = 0;
  constexpr int kFields = 300000;
  for (int i = 0; i < kFields; ++i) {
    std::string text;
    char buffer[96];
    switch (i % 4) {
      case 0: {  // shortest round-trip spelling of a double of IMU size
        const double magnitude =
            std::ldexp(static_cast<double>(rng() >> 11), -53 - int(rng() % 20));
        const std::to_chars_result r = std::to_chars(buffer,
                                                     buffer + sizeof(buffer),
                                                     rng() & 1 ? -magnitude : magnitude,
                                                     std::chars_format::fixed);
        text.assign(buffer, r.ptr);
        break;
      }
      case 1: {  // 1 to 7 digits, a point, 1 to 24 digits, leading zeros now and then
        if (rng() & 1) text += '-';
        const int before = 1 + int(rng() % 7);
        const int after = 1 + int(rng() % 24);
        const int zeros = rng() % 3 == 0 ? int(rng() % (before + after)) : 0;
        for (int k = 0; k < before + after; ++k) {
          if (k == before) text += '.';
          text += static_cast<char>('0' + (k < zeros ? 0 : rng() % 10));
        }
        break;
      }
      case 2: {  // 17 to 19 significant digits next to the midpoint of two doubles
        const double low = std::ldexp(static_cast<double>((rng() >> 11) | (uint64_t{1} << 52)),
                                      -52 - int(rng() % 24) + 8);
        const long double middle = static_cast<long double>(low) +
                                   (static_cast<long double>(std::nextafter(low, 1e300)) - low) / 2;
        std::snprintf(buffer, sizeof(buffer), "%.*Lf", 18 + int(rng() % 12), middle);
        text = buffer;
        // Keep 17 to 19 significant digits, then move the last one by -1, 0 or +1.
        const size_t first = text.find_first_not_of("0.");
        size_t keep = first;
        for (int digits = 0; keep < text.size() && digits < 17 + int(rng() % 3); ++keep) {
          if (text[keep] != '.') ++digits;
        }
        text.resize(keep);
        if (text.back() != '.') {
          const int moved = text.back() - '0' + int(rng() % 3) - 1;
          if (moved >= 0 && moved <= 9) text.back() = static_cast<char>('0' + moved);
        }
        break;
      }
      default: {  // integers of 1 to 20 digits
        const int digits = 1 + int(rng() % 20);
        for (int k = 0; k < digits; ++k) text += static_cast<char>('0' + rng() % 10);
      }
    }
    double value = 0.0;
    read += Field(text, static_cast<uint32_t>(i)).Decimal(&value) ? 1 : 0;
    ASSERT_TRUE(SameAsFromChars(text, static_cast<uint32_t>(i)));
  }
  // Most decimals take the fast path (the rest: too long, no point, a tie nearby).
  EXPECT_GT(read, kFields / 2);
}

}  // namespace
}  // namespace internal
}  // namespace splinecal
