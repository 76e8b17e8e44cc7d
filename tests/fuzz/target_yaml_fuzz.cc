// Fuzzes the calibration target YAML reader and its writer's read-back (io/target_yaml.h). The
// reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("target_yaml")
