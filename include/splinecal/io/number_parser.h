// A fast path for the numbers of large text files (internal to io/; used by the parallel EuRoC
// reader, io/parallel_euroc_imu.h, which knows where each field ends before it reads the field).
// A 10^7-row IMU file holds 7 * 10^7 numbers. std::from_chars (Eisel-Lemire in libstdc++ 12)
// reads one digit at a time and spends much of its time on the branches that follow the digits.
// Here a field of at most 32 characters is read right-aligned in two SSE2 registers: the digits
// are checked and combined into four 8-digit groups in a few vector instructions, the double is
// then rounded with 128-bit integer arithmetic.
//
// The result is exactly what std::from_chars gives, bit for bit, or nothing: the functions return
// false for anything they do not handle (an exponent, a '+', inf or nan, more than 19
// significant digits, a value within 2^-64 of its last bit from halfway between two doubles, a
// platform without SSE2) and the caller then uses ParseNumberPrefix (io/text_file.h).
//
// How the double is rounded: w * 10^q (w < 10^19, |q| small) is multiplied as w * T, where T is
// 10^q scaled to 128 bits and rounded down. The true product lies within one unit of the 64th bit
// below the top 128 bits of w * T, so the 53 bits of the result and the rounding direction are
// known unless those 128 bits lie within two units below the halfway point: then false.
#ifndef SPLINECAL_IO_NUMBER_PARSER_H_
#define SPLINECAL_IO_NUMBER_PARSER_H_

#include <cstdint>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace splinecal {
namespace internal {

// 10^q for q in [kMinPow10, kMaxPow10] as T * 2^exponent2, T = (high, low) in [2^127, 2^128)
// rounded down (exact for q = 0).
struct ScaledPow10 {
  uint64_t high;
  uint64_t low;
  int exponent2;
};
inline constexpr int kMinPow10 = -32;
inline constexpr int kMaxPow10 = 0;  // fields without an exponent: q = -(digits after the point)
struct ScaledPow10Table {
  ScaledPow10 of[kMaxPow10 - kMinPow10 + 1];  // index q - kMinPow10
};
extern const ScaledPow10Table kScaledPow10;

// The fields are read right-aligned: the kFieldWindow bytes before a field's end must be readable
// (they may belong to earlier fields or lines), and a field is at most that long.
inline constexpr int kFieldWindow = 32;

// The double nearest to (-1)^negative * w * 10^q, as std::from_chars rounds it (ties to even);
// false when w * 10^q is too close to a tie to decide here, or q is outside the table.
inline bool DecimalToDouble(uint64_t w, int q, bool negative, double* value) {
  if (w == 0) {
    *value = negative ? -0.0 : 0.0;
    return true;
  }
  if (q < kMinPow10 || q > kMaxPow10) return false;
  const ScaledPow10& t = kScaledPow10.of[q - kMinPow10];
  const int shift = __builtin_clzll(w);
  const uint64_t wn = w << shift;  // top bit set
  // wn * T has 192 bits; the bits that decide the rounding are its top 128. The high product
  // A = wn * T.high is most of them: the true value (T rounded down by less than 1, times wn <
  // 2^64, plus wn * T.low < 2^128) lies in [A, A + 2^64) units of A's lowest bit.
  unsigned __int128 product = static_cast<unsigned __int128>(wn) * t.high;
  // wn >= 2^63 and T >= 2^127: the top bit is bit 127 or 126 of the 128. Below the 53 bits of the
  // result lie 11 or 10 bits of the upper word (the remainder R, to compare with half =
  // 2^(bits - 1)) and the whole lower word.
  auto split = [](unsigned __int128 x, uint64_t* upper, int* low_bits, uint64_t* remainder) {
    *upper = static_cast<uint64_t>(x >> 64);
    *low_bits = 10 + static_cast<int>(*upper >> 63);
    *remainder = *upper & ((uint64_t{1} << *low_bits) - 1);
  };
  uint64_t upper = 0;
  int low_bits = 0;
  uint64_t remainder = 0;
  split(product, &upper, &low_bits, &remainder);
  uint64_t half = uint64_t{1} << (low_bits - 1);
  // R <= half - 2: down, whatever the lower words add; R >= half + 1: up (a carry into the
  // mantissa then rounds down to the same value). Only R = half - 1 or half needs the low product
  // (once in 2^9): then the top 128 bits, exact within [H, H + 2) units of their lowest bit.
  if (remainder + 1 == half || remainder == half) {
    product += static_cast<uint64_t>((static_cast<unsigned __int128>(wn) * t.low) >> 64);
    split(product, &upper, &low_bits, &remainder);
    half = uint64_t{1} << (low_bits - 1);
    const uint64_t middle = static_cast<uint64_t>(product);
    if ((remainder == half && middle == 0) || (remainder == half - 1 && middle == ~uint64_t{0})) {
      return false;  // R = half or half - 1 (H's lower word aside): a tie may lie in [H, H + 2)
    }
    // Otherwise the remainder with the lower word is >= half + 1 or <= half - 2.
  }
  uint64_t mantissa = (upper >> low_bits) + (remainder >= half ? 1 : 0);
  int exponent2 = low_bits + 128 + t.exponent2 - shift;  // value = mantissa * 2^exponent2
  if (mantissa == (uint64_t{1} << 53)) {                 // rounded up to the next power of two
    mantissa >>= 1;
    ++exponent2;
  }
  // -32 <= q <= 0 and w < 2^64 keep the value far from overflow and from subnormals.
  const uint64_t bits = (uint64_t{negative} << 63) |
                        (static_cast<uint64_t>(exponent2 + 52 + 1023) << 52) |
                        (mantissa & ((uint64_t{1} << 52) - 1));
  std::memcpy(value, &bits, 8);
  return true;
}

#if defined(__SSE2__)

// 32 bytes loaded at kRamp + k are 0 before index 32 - k and 0xFF from there on.
struct Ramp {
  alignas(64) unsigned char bytes[64];
  constexpr Ramp() : bytes() {
    for (int i = 32; i < 64; ++i) bytes[i] = 0xFF;
  }
};
inline constexpr Ramp kRamp{};

inline __m128i Load(const void* p) { return _mm_loadu_si128(static_cast<const __m128i*>(p)); }

// One bit per byte of the 32 bytes (lo, hi): the bytes where `bytes` is true (0xFF).
inline uint32_t Mask32(__m128i lo, __m128i hi) {
  return static_cast<uint32_t>(_mm_movemask_epi8(lo)) |
         (static_cast<uint32_t>(_mm_movemask_epi8(hi)) << 16);
}

// Bytes that are not digits, given x = byte - '0' (as signed bytes: a digit is 0..9).
inline uint32_t NonDigits(__m128i x_lo, __m128i x_hi) {
  const __m128i zero = _mm_setzero_si128();
  const __m128i nine = _mm_set1_epi8(9);
  return Mask32(_mm_or_si128(_mm_cmplt_epi8(x_lo, zero), _mm_cmpgt_epi8(x_lo, nine)),
                _mm_or_si128(_mm_cmplt_epi8(x_hi, zero), _mm_cmpgt_epi8(x_hi, nine)));
}

// The number whose 32 decimal digits are the bytes of (d_lo, d_hi), most significant first
// (values 0..9, zeros before the number); false when it has more than 19 digits. Pairs, quads and
// octets are combined by multiply-adds of 16-bit lanes.
inline bool DigitsValue(__m128i d_lo, __m128i d_hi, uint64_t* w) {
  const __m128i zero = _mm_setzero_si128();
  const __m128i ten_one = _mm_set1_epi32(0x0001000A);  // 16-bit lanes (10, 1)
  const __m128i hundred_one = _mm_set1_epi32(0x00010064);
  const __m128i ten_thousand_one = _mm_set1_epi32(0x00012710);
  const __m128i pairs_lo = _mm_packs_epi32(_mm_madd_epi16(_mm_unpacklo_epi8(d_lo, zero), ten_one),
                                           _mm_madd_epi16(_mm_unpackhi_epi8(d_lo, zero), ten_one));
  const __m128i pairs_hi = _mm_packs_epi32(_mm_madd_epi16(_mm_unpacklo_epi8(d_hi, zero), ten_one),
                                           _mm_madd_epi16(_mm_unpackhi_epi8(d_hi, zero), ten_one));
  const __m128i quads =
      _mm_packs_epi32(_mm_madd_epi16(pairs_lo, hundred_one), _mm_madd_epi16(pairs_hi, hundred_one));
  alignas(16) uint32_t groups[4];  // 8 digits each
  _mm_store_si128(reinterpret_cast<__m128i*>(groups), _mm_madd_epi16(quads, ten_thousand_one));
  if (groups[0] != 0 || groups[1] >= 1000) return false;  // w >= 10^19
  *w = (uint64_t{groups[1]} * 100000000 + groups[2]) * 100000000 + groups[3];
  return true;
}

// The field [begin, end) when it is "[-]digits.digits" (at least one digit on each side, at most
// 19 significant digits, at most kFieldWindow characters), as std::from_chars reads it.
inline bool ParseDecimalField(const char* begin, const char* end, double* value) {
  const int n = static_cast<int>(end - begin);
  if (n < 3 || n > kFieldWindow) return false;
  const __m128i zero_char = _mm_set1_epi8('0');
  const __m128i x_lo = _mm_sub_epi8(Load(end - 32), zero_char);
  const __m128i x_hi = _mm_sub_epi8(Load(end - 16), zero_char);
  const __m128i point_char = _mm_set1_epi8('.' - '0');
  const uint32_t points =
      Mask32(_mm_cmpeq_epi8(x_lo, point_char), _mm_cmpeq_epi8(x_hi, point_char));
  // Byte i of the window holds field character i - (32 - n).
  const uint32_t field = static_cast<uint32_t>(~uint64_t{0} << (32 - n));
  const bool negative = *begin == '-';
  const uint32_t sign = negative ? uint32_t{1} << (32 - n) : 0;
  const uint32_t point = points & field;
  if (point == 0 || (point & (point - 1)) != 0 ||
      (NonDigits(x_lo, x_hi) & field & ~point & ~sign) != 0) {
    return false;  // not exactly one point with digits (and a leading '-') around it
  }
  const int point_index = __builtin_ctz(point);
  const int fraction_digits = 31 - point_index;
  const int first_digit = 32 - n + (negative ? 1 : 0);
  if (fraction_digits == 0 || point_index == first_digit) return false;
  // The digits before the point move one byte towards the end, over the point: the field's digits
  // then form one number, w, in bytes first_digit + 1 .. 31.
  const __m128i moved_lo = _mm_slli_si128(x_lo, 1);
  const __m128i moved_hi = _mm_or_si128(_mm_slli_si128(x_hi, 1), _mm_srli_si128(x_lo, 15));
  const unsigned char* const fraction = kRamp.bytes + fraction_digits;  // from point_index + 1
  const __m128i fraction_lo = Load(fraction);
  const __m128i fraction_hi = Load(fraction + 16);
  const unsigned char* const digits = kRamp.bytes + (31 - first_digit);  // from first_digit + 1
  const __m128i d_lo = _mm_and_si128(
      _mm_or_si128(_mm_and_si128(x_lo, fraction_lo), _mm_andnot_si128(fraction_lo, moved_lo)),
      Load(digits));
  const __m128i d_hi = _mm_and_si128(
      _mm_or_si128(_mm_and_si128(x_hi, fraction_hi), _mm_andnot_si128(fraction_hi, moved_hi)),
      Load(digits + 16));
  uint64_t w = 0;
  return DigitsValue(d_lo, d_hi, &w) && DecimalToDouble(w, -fraction_digits, negative, value);
}

// The field [begin, end) when it is 1 to 19 digits (no sign) below 2^63.
inline bool ParseInt64Field(const char* begin, const char* end, int64_t* value) {
  const int n = static_cast<int>(end - begin);
  if (n < 1 || n > 19) return false;
  const __m128i zero_char = _mm_set1_epi8('0');
  const __m128i x_lo = _mm_sub_epi8(Load(end - 32), zero_char);
  const __m128i x_hi = _mm_sub_epi8(Load(end - 16), zero_char);
  const unsigned char* const digits = kRamp.bytes + n;  // from index 32 - n
  const __m128i keep_lo = Load(digits);
  const __m128i keep_hi = Load(digits + 16);
  if ((NonDigits(x_lo, x_hi) & Mask32(keep_lo, keep_hi)) != 0) return false;
  uint64_t w = 0;
  if (!DigitsValue(_mm_and_si128(x_lo, keep_lo), _mm_and_si128(x_hi, keep_hi), &w) ||
      w > static_cast<uint64_t>(INT64_MAX)) {
    return false;
  }
  *value = static_cast<int64_t>(w);
  return true;
}
#else
// Without SSE2 every field goes to ParseNumberPrefix.
inline bool ParseDecimalField(const char*, const char*, double*) { return false; }
inline bool ParseInt64Field(const char*, const char*, int64_t*) { return false; }
#endif

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_IO_NUMBER_PARSER_H_
