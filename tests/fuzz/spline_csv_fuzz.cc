// Fuzzes the spline.csv reader, its writer's read-back and evaluation at the range ends
// (io/spline_csv.h). The reader and the properties checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("spline_csv")
