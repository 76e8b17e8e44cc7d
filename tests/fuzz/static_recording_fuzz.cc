// Fuzzes allan's own readers: EuRoC imu0/data.csv on both paths, and plain columns.
// The reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("static_recording")
