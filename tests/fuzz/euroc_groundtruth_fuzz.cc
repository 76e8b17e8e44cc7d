// Fuzzes the EuRoC ground-truth reader (io/euroc.h).
#include "fuzz_input.h"
#include "splinecal/error.h"
#include "splinecal/io/euroc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = splinecal::fuzz::WriteInput(data, size, ".csv");
  try {
    splinecal::ReadEurocGroundTruth(path);
  } catch (const splinecal::Error&) {
  }
  return 0;
}
