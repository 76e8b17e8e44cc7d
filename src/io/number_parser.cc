#include "splinecal/io/number_parser.h"

namespace splinecal {
namespace internal {
namespace {

// floor(2^kScale2 / 10^k) for k = 0 .. 32 as unsigned integers of 16 32-bit words (little-endian):
// 2^480 / 10^32 > 2^373 keeps far more than the 128 significant bits the table takes.
constexpr int kWords = 16;
constexpr int kScale2 = 480;
struct BigNumber {
  uint32_t word[kWords] = {};
};

// Exact floor division: floor(floor(x / 10) / 10) = floor(x / 100), and so on.
constexpr void DivideByTen(BigNumber* x) {
  uint64_t remainder = 0;
  for (int i = kWords - 1; i >= 0; --i) {
    const uint64_t v = (remainder << 32) | x->word[i];
    x->word[i] = static_cast<uint32_t>(v / 10);
    remainder = v % 10;
  }
}

// x * 2^scale2 as T * 2^exponent2 with T the top 128 bits of x (the bits below are dropped:
// rounded down). x is at least 2^128 here, so T <= 10^q * 2^-exponent2 < T + 1.
constexpr ScaledPow10 Top128Bits(const BigNumber& x, int scale2) {
  int top = kWords * 32 - 1;
  while (((x.word[top / 32] >> (top % 32)) & 1) == 0) --top;
  ScaledPow10 result{0, 0, top - 127 + scale2};
  for (int i = 0; i < 128; ++i) {
    const int bit = top - i;
    const uint64_t v = (x.word[bit / 32] >> (bit % 32)) & 1;
    if (i < 64) {
      result.high |= v << (63 - i);
    } else {
      result.low |= v << (127 - i);
    }
  }
  return result;
}

constexpr ScaledPow10Table BuildTable() {
  ScaledPow10Table table{};
  BigNumber inverse;  // floor(2^480 / 10^-q)
  inverse.word[kScale2 / 32] = uint32_t{1} << (kScale2 % 32);
  for (int q = 0; q >= kMinPow10; --q) {
    table.of[q - kMinPow10] = Top128Bits(inverse, -kScale2);
    DivideByTen(&inverse);
  }
  return table;
}

}  // namespace

// Computed by the compiler: exact by construction, not typed in.
constexpr ScaledPow10Table kScaledPow10 = BuildTable();

}  // namespace internal
}  // namespace splinecal
