// Fuzzes Kalibr's IMU result file reader (io/imu_models_yaml.h: simulate --imu-intrinsics,
// correct --imu-intrinsics) with a write-and-read-back check. The reader and the properties
// checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("imu_models_yaml")
