#include "splinecal/string_printf.h"

#include <cstdarg>
#include <cstdio>

namespace splinecal {

std::string StringPrintf(const char* format, ...) {
  va_list args;
  va_start(args, format);
  va_list retry;
  va_copy(retry, args);
  // Most results fit a small stack buffer; only longer ones pay for a second pass.
  char small[512];
  const int length = std::vsnprintf(small, sizeof(small), format, args);
  va_end(args);
  std::string text;
  if (length >= 0 && static_cast<size_t>(length) < sizeof(small)) {
    text.assign(small, static_cast<size_t>(length));
  } else if (length >= 0) {
    text.resize(static_cast<size_t>(length));
    // The string's terminating null (text.data()[length], writable since C++17) takes the null
    // vsnprintf writes.
    std::vsnprintf(text.data(), text.size() + 1, format, retry);
  }  // length < 0 is an encoding error: the result stays empty.
  va_end(retry);
  return text;
}

std::string FormatDouble(double value) { return StringPrintf("%.17g", value); }

}  // namespace splinecal
