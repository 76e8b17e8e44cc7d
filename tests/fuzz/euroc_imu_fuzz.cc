// Fuzzes the EuRoC IMU reader (io/euroc.h).
#include "fuzz_input.h"
#include "splinecal/error.h"
#include "splinecal/io/euroc.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = splinecal::fuzz::WriteInput(data, size, ".csv");
  try {
    splinecal::ReadEurocImu(path);
  } catch (const splinecal::Error&) {
  }
  return 0;
}
