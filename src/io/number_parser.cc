#include "splinecal/io/number_parser.h"

#include "splinecal/io/detail/number_parser_avx2.h"

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

#if defined(SPLINECAL_HAS_AVX2_PARSER)
constexpr double PowerOfTwo(int e) {
  double x = 1.0;
  for (; e > 0; --e) x *= 2.0;
  for (; e < 0; ++e) x *= 0.5;
  return x;
}

// v * 2^e2 rounded to the nearest double (ties to even), v > 0.
constexpr double RoundToDouble(unsigned __int128 v, int e2) {
  int top = 127;
  while (((v >> top) & 1) == 0) --top;
  if (top < 53) return static_cast<double>(static_cast<uint64_t>(v)) * PowerOfTwo(e2);
  const int dropped = top - 52;
  uint64_t kept = static_cast<uint64_t>(v >> dropped);
  const unsigned __int128 rest = v & ((static_cast<unsigned __int128>(1) << dropped) - 1);
  const unsigned __int128 half = static_cast<unsigned __int128>(1) << (dropped - 1);
  if (rest > half || (rest == half && (kept & 1) != 0)) ++kept;  // kept <= 2^53: exact
  return static_cast<double>(kept) * PowerOfTwo(e2 + dropped);
}

// high = T * 2^e rounded, low = the rest rounded: high + low is within 2^-106 of 10^-k.
constexpr DoubleDoublePow10Table BuildDoubleDoubleTable(const ScaledPow10Table& scaled) {
  DoubleDoublePow10Table table{};
  for (int k = 0; k <= -kMinPow10; ++k) {
    const ScaledPow10& t = scaled.of[-k - kMinPow10];
    const unsigned __int128 value = (static_cast<unsigned __int128>(t.high) << 64) | t.low;
    // The top bit is bit 127: high keeps 53 bits, 75 are dropped.
    const unsigned __int128 rest = value & ((static_cast<unsigned __int128>(1) << 75) - 1);
    const unsigned __int128 half = static_cast<unsigned __int128>(1) << 74;
    const bool up = rest > half || (rest == half && ((value >> 75) & 1) != 0);
    table.high[k] = RoundToDouble(value, t.exponent2);
    table.low[k] =
        up ? -RoundToDouble((static_cast<unsigned __int128>(1) << 75) - rest, t.exponent2)
           : (rest == 0 ? 0.0 : RoundToDouble(rest, t.exponent2));
  }
  return table;
}
#endif

}  // namespace

// Computed by the compiler: exact by construction, not typed in.
constexpr ScaledPow10Table kScaledPow10 = BuildTable();

#if defined(SPLINECAL_HAS_AVX2_PARSER)
constexpr DoubleDoublePow10Table kDoubleDoublePow10 = BuildDoubleDoubleTable(kScaledPow10);

bool CpuHasAvx2Parser() {
  static const bool has = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma") &&
                          __builtin_cpu_supports("bmi") && __builtin_cpu_supports("bmi2") &&
                          __builtin_cpu_supports("popcnt");
  return has;
}
#endif

}  // namespace internal
}  // namespace splinecal
