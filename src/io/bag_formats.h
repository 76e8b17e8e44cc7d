// The readers behind OpenBag (io/bag_reader.h), one per format (private to src/io/).
#ifndef SPLINECAL_SRC_IO_BAG_FORMATS_H_
#define SPLINECAL_SRC_IO_BAG_FORMATS_H_

#include <memory>
#include <string>
#include <vector>

#include "splinecal/io/bag_reader.h"

namespace splinecal {
namespace internal {

// ROS 1 bag format 2.0 (wiki.ros.org/Bags/Format/2.0); several files are one split recording.
std::unique_ptr<BagReader> OpenRos1Bags(const std::vector<std::string>& paths);
// MCAP (mcap.dev/spec), one file.
std::unique_ptr<BagReader> OpenMcap(const std::string& path);
// rosbag2's sqlite3 storage: `db3_paths` read as one recording.
std::unique_ptr<BagReader> OpenRosbag2Sqlite(const std::vector<std::string>& db3_paths);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_IO_BAG_FORMATS_H_
