// Fuzzes the Kalibr camchain.yaml reader and its writer's read-back (io/camchain_yaml.h). The
// reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("camchain_yaml")
