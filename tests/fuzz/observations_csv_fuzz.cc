// Fuzzes the observations.csv reader and its writer's read-back (io/observations_csv.h). The reader
// and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("observations_csv")
