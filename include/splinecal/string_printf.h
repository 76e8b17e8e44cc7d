// The one printf-style formatter of splinecal, for messages and for the numbers in every output
// file. printf conversions (%.3g, %.17g) say in one place how a number is shown; iostreams would
// need manipulators per value. Use these instead of a local char buffer and snprintf, which
// silently truncates when the buffer is too small.
#ifndef SPLINECAL_STRING_PRINTF_H_
#define SPLINECAL_STRING_PRINTF_H_

#include <string>

namespace splinecal {

// Returns the text printf(format, ...) would print, whole: the result is sized by a first
// vsnprintf pass, so nothing is ever truncated. The compiler checks the arguments against the
// format.
std::string StringPrintf(const char* format, ...) __attribute__((format(printf, 1, 2)));

// A double with 17 significant digits ("%.17g": reads back bit-exactly), the one number format
// of every splinecal data file (docs/conventions.md, "Time").
std::string FormatDouble(double value);

}  // namespace splinecal

#endif  // SPLINECAL_STRING_PRINTF_H_
