// Fuzzes the pose-source reader (io/poses.h: TUM or EuRoC, detected), which fit, align, calibrate
// and simulate use. The reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("poses")
