// The numerical constants and unit conversions every area shares, written once (docs/conventions.md
// "Time": SI units inside, nanoseconds for timestamps, degrees only at the user's end).
#ifndef SPLINECAL_UNITS_H_
#define SPLINECAL_UNITS_H_

#include <cmath>
#include <cstdint>

namespace splinecal {

inline constexpr double kPi = 3.14159265358979323846;
inline constexpr double kRadToDeg = 180.0 / kPi;
inline constexpr double kDegToRad = kPi / 180.0;

inline constexpr int64_t kNanosecondsPerSecond = 1'000'000'000;

// Seconds of a nanosecond count (or difference).
constexpr double NanosecondsToSeconds(int64_t t_ns) { return 1e-9 * static_cast<double>(t_ns); }

}  // namespace splinecal

#endif  // SPLINECAL_UNITS_H_
