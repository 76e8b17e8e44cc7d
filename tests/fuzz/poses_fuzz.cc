// Fuzzes the pose-source reader (io/poses.h: TUM or EuRoC, detected).
#include "fuzz_input.h"
#include "splinecal/error.h"
#include "splinecal/io/poses.h"

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string& path = splinecal::fuzz::WriteInput(data, size, ".txt");
  try {
    splinecal::ReadPoses(path);
  } catch (const splinecal::Error&) {
  }
  return 0;
}
