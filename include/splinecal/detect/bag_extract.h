// `splinecal bag extract` as a library function (docs/bags.md): a recording's IMU and image
// topics written as the EuRoC/ASL folders every other command reads (imu0/data.csv,
// cam0/data.csv + cam0/data/<t_ns>.png), streamed one message at a time. The command line and the
// Python module's bag_extract both run it.
#ifndef SPLINECAL_DETECT_BAG_EXTRACT_H_
#define SPLINECAL_DETECT_BAG_EXTRACT_H_

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/output_dir.h"

namespace splinecal {

// One extracted topic and the folder it becomes.
struct ExtractedTopic {
  int topic = 0;           // index into BagReader::topics()
  std::string folder;      // "imu0", "cam0"
  std::vector<ImuSample> imu;
  std::string frames_csv;  // an image topic's data.csv
  int64_t messages = 0;
  int64_t first_t_ns = 0;  // as written (header stamp or receive time)
  int64_t last_t_ns = 0;
};

struct BagExtractOptions {
  std::vector<std::string> topics;  // in this order; empty: every IMU and image topic, by name
  BagTime time = BagTime::kHeader;
  // Called every 1000 messages with the count so far.
  std::function<void(int64_t)> progress;
};

// The topics `options.topics` names (all readable ones when empty), each with its folder: IMU
// topics become imu0, imu1, ..., image topics cam0, cam1, ... in the order given. Throws
// splinecal::Error naming --topics for a topic the recording lacks (with its IMU and image
// topics) or of another type, and for a recording with nothing to extract (`name` names it).
std::vector<ExtractedTopic> ChooseExtractedTopics(const BagReader& bag,
                                                  const BagExtractOptions& options,
                                                  const std::string& name);

// Reads every message of the chosen topics, with the checks of bag_messages.h (stamps of a topic
// strictly increasing, images that decode). With `output`, stages the folders' files in it
// (data.csv, PNGs); nullptr reads and checks only. The caller commits `output`.
std::vector<ExtractedTopic> ExtractBag(BagReader* bag, const BagExtractOptions& options,
                                       const std::string& name, OutputDir* output);

// result.yaml of an extraction: the recording, its format, the clock, and which topic became
// which folder with its count and time range.
std::string BagExtractResultYaml(const BagReader& bag, const std::vector<std::string>& paths,
                                 const std::string& bag_time,
                                 const std::vector<ExtractedTopic>& topics);

}  // namespace splinecal

#endif  // SPLINECAL_DETECT_BAG_EXTRACT_H_
