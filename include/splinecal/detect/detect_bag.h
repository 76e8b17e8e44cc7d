// `splinecal detect --bag`: the target's corners in the image topics of a recording (ROS 1 bag,
// MCAP, rosbag2 sqlite3; io/bag_reader.h), as DetectFolders finds them in image folders
// (detect/detect_folders.h): the same workers, the same checks, the same observations. The bag
// is streamed: each worker holds the one message it decodes, never the bag (docs/bags.md,
// "Commands on a bag").
#ifndef SPLINECAL_DETECT_DETECT_BAG_H_
#define SPLINECAL_DETECT_DETECT_BAG_H_

#include <string>
#include <vector>

#include "splinecal/camera/target.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/io/bag_messages.h"

namespace splinecal {

struct BagImageSource {
  std::vector<std::string> paths;   // the recording (OpenBag's paths)
  std::vector<std::string> topics;  // topic i is camera i
  BagTime time = BagTime::kHeader;  // a frame's t_ns: its header stamp or its receive time
};

// Throws splinecal::Error for a bag OpenBag refuses, no topic, a topic the recording lacks (naming
// its image topics), a topic that is not sensor_msgs/Image or CompressedImage, a topic given
// twice, times of a topic that do not increase (the first offending message), a damaged bag, and
// for what DetectFolders throws. A camera's `dir` in the summaries is "FILE:TOPIC".
DetectFoldersResult DetectBag(const BagImageSource& source,
                              const CalibrationTarget& target,
                              const DetectFoldersOptions& options);

// Opens the recording and checks the topics as DetectBag does, reading no message (the
// command's input stage, Command::read_inputs).
void CheckBagImageSource(const BagImageSource& source);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_DETECT_BAG_H_
