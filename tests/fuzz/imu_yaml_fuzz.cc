// Fuzzes YAML loading (io/yaml_document.h) through the Kalibr imu.yaml reader and the generic
// lookups every YAML reader uses. The reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("imu_yaml")
