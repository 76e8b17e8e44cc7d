// Fuzzes the EuRoC IMU reader (io/euroc.h). The reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("euroc_imu")
