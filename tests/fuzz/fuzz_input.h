// libFuzzer plumbing shared by the fuzz targets: splinecal's readers take paths, so each input is
// written to a per-process temporary file and the reader runs on it. A target passes when the
// reader returns or throws splinecal::Error; anything else (a crash, a sanitizer report, another
// exception, a hang) is a finding.
#ifndef SPLINECAL_TESTS_FUZZ_FUZZ_INPUT_H_
#define SPLINECAL_TESTS_FUZZ_FUZZ_INPUT_H_

#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <string>

namespace splinecal {
namespace fuzz {

// A temporary path of this process ending in `name` (one process fuzzes one input at a time).
inline std::string TempPath(const std::string& name) {
  return "/tmp/splinecal-fuzz-" + std::to_string(::getpid()) + "-" + name;
}

// Writes the bytes to `path`; a failure to write is the harness's fault, not a finding.
inline void WriteFileOrTrap(const std::string& path, const void* data, size_t size) {
  std::FILE* file = std::fopen(path.c_str(), "wb");
  if (file == nullptr) __builtin_trap();
  if (size > 0 && std::fwrite(data, 1, size, file) != size) __builtin_trap();
  std::fclose(file);
}

inline std::string WriteInput(const uint8_t* data, size_t size, const char* suffix) {
  const std::string path = TempPath(std::string("input") + suffix);
  WriteFileOrTrap(path, data, size);
  return path;
}

}  // namespace fuzz
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_FUZZ_FUZZ_INPUT_H_
