// Fuzzes the bag readers (io/bag_reader.h: ROS 1, MCAP, rosbag2 sqlite3), the message parsers
// and the image conversion behind them. The reader and the property checked are in readers.h.
#include "readers.h"

SPLINECAL_READER_FUZZER("bag")
