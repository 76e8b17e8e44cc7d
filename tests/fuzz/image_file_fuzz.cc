// Fuzzes the PNG and JPEG decoders and the AprilGrid detector behind them (detect/image_file.h,
// detect/target_detector.h). The reader and the property checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("image_file")
