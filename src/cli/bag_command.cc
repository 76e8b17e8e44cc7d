// `splinecal bag info` and `splinecal bag extract`: ROS 1 bags, MCAP files and rosbag2 sqlite3
// recordings (io/bag_reader.h, docs/bags.md) listed like `rosbag info`, and turned into the
// EuRoC/ASL folders every other command reads.
#include <gflags/gflags.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <memory>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/detect/bag_extract.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/string_printf.h"

DEFINE_string(bags,
              "",
              "The recording: ROS 1 bags (several: one split recording), an MCAP file, or a "
              "rosbag2 folder, its metadata.yaml or its .db3 files [paths, comma-separated; "
              "also taken without the flag]");
DEFINE_string(topics,
              "",
              "Topics to extract, comma-separated; empty: every sensor_msgs/Imu, Image and "
              "CompressedImage topic");

namespace splinecal {
namespace cli {
namespace {

// Seconds.nanoseconds of an int64 [ns] stamp, exactly (no double).
std::string StampText(int64_t t_ns) {
  const char* sign = t_ns < 0 ? "-" : "";
  const uint64_t magnitude = t_ns < 0 ? -static_cast<uint64_t>(t_ns) : static_cast<uint64_t>(t_ns);
  return StringPrintf("%s%" PRIu64 ".%09" PRIu64, sign, magnitude / 1'000'000'000,
                      magnitude % 1'000'000'000);
}

std::string SizeText(int64_t bytes) {
  if (bytes < 1024) return StringPrintf("%lld bytes", static_cast<long long>(bytes));
  if (bytes < (int64_t{1} << 20)) return StringPrintf("%.1f KiB", bytes / 1024.0);
  if (bytes < (int64_t{1} << 30)) return StringPrintf("%.1f MiB", bytes / 1048576.0);
  return StringPrintf("%.2f GiB", bytes / 1073741824.0);
}

std::unique_ptr<BagReader> OpenBagFlag() {
  return OpenBag(ListFlag("bags", RequiredFlag("bags", FLAGS_bags)));
}

void PrintWarnings(const BagReader& bag) {
  for (const std::string& warning : bag.warnings()) {
    std::fprintf(stderr, "warning: %s\n", warning.c_str());
  }
}

int RunBagInfo() {
  const std::unique_ptr<BagReader> bag = OpenBagFlag();
  PrintWarnings(*bag);
  int64_t messages = 0;
  int64_t start = INT64_MAX;
  int64_t end = INT64_MIN;
  size_t name_width = 5;
  size_t type_width = 4;
  for (const BagTopic& topic : bag->topics()) {
    messages += topic.message_count;
    name_width = std::max(name_width, topic.name.size());
    type_width = std::max(type_width, topic.type.size());
    if (topic.message_count == 0) continue;
    start = std::min(start, topic.first_time_ns);
    end = std::max(end, topic.last_time_ns);
  }
  std::printf("path:      %s\n", FLAGS_bags.c_str());
  std::printf("format:    %s\n", bag->format().c_str());
  std::printf("size:      %s\n", SizeText(bag->file_bytes()).c_str());
  if (messages > 0) {
    std::printf("start:     %s s (recording time)\n", StampText(start).c_str());
    std::printf("end:       %s s\n", StampText(end).c_str());
    std::printf("duration:  %.3f s\n", (end - start) * 1e-9);
  }
  std::printf("messages:  %lld\n", static_cast<long long>(messages));
  std::printf("topics:\n");
  std::vector<BagTopic> topics = bag->topics();
  std::sort(topics.begin(), topics.end(),
            [](const BagTopic& a, const BagTopic& b) { return a.name < b.name; });
  for (const BagTopic& topic : topics) {
    std::string line = StringPrintf("  %-*s %7lld msg%s  %-*s", static_cast<int>(name_width),
                                    topic.name.c_str(),
                                    static_cast<long long>(topic.message_count),
                                    topic.message_count == 1 ? " " : "s",
                                    static_cast<int>(type_width), topic.type.c_str());
    if (topic.message_count > 1 && topic.last_time_ns > topic.first_time_ns) {
      line += StringPrintf("  %8.3f Hz  max gap %.1f ms",
                           (topic.message_count - 1) * 1e9 /
                               static_cast<double>(topic.last_time_ns - topic.first_time_ns),
                           topic.max_gap_ns * 1e-6);
    }
    if (KindOfType(topic.type) == BagMessageKind::kOther) line += "  (not read by splinecal)";
    while (!line.empty() && line.back() == ' ') line.pop_back();
    std::printf("%s\n", line.c_str());
  }
  return 0;
}

BagExtractOptions ExtractOptionsFromFlags() {
  BagExtractOptions options;
  options.topics = ListFlag("topics", FLAGS_topics);
  options.time = ParseBagTime(FLAGS_bag_time);
  options.progress = [](int64_t done) {
    Progress(StringPrintf("bag extract: %lld messages", static_cast<long long>(done)));
  };
  return options;
}

int RunBagExtract() {
  const std::unique_ptr<BagReader> bag = OpenBagFlag();
  PrintWarnings(*bag);
  const BagExtractOptions options = ExtractOptionsFromFlags();
  // Refuses a bad --topics before the output folder is made.
  ChooseExtractedTopics(*bag, options, FLAGS_bags);
  OutputDir output(RequiredFlag("out", FLAGS_out));
  const std::vector<ExtractedTopic> topics = ExtractBag(bag.get(), options, FLAGS_bags, &output);
  for (const ExtractedTopic& topic : topics) {
    std::printf("%-5s <- %s (%lld messages, %s)\n", topic.folder.c_str(),
                bag->topics()[topic.topic].name.c_str(), static_cast<long long>(topic.messages),
                bag->topics()[topic.topic].type.c_str());
  }
  output.WriteFile("result.yaml", BagExtractResultYaml(*bag, ListFlag("bags", FLAGS_bags),
                                                       FLAGS_bag_time, topics));
  output.Commit();
  return 0;
}

}  // namespace

Command BagInfoCommand() {
  return {"bag info",
          "list a bag's topics: types, counts, rates, time range, gaps",
          "splinecal bag info FILE... [--bags FILE,...]",
          "Lists the topics of a ROS 1 bag (several files: one split recording), an MCAP file or\n"
          "a rosbag2 sqlite3 recording (its folder, metadata.yaml or .db3 files), as rosbag info\n"
          "does: message type, count, rate and longest gap in recording time, and the time\n"
          "range. Topics splinecal cannot read are listed and marked. A bag that was not closed\n"
          "(no index) is read by a linear scan, with a warning.",
          {{"bags", ""}},
          &RunBagInfo,
          [] { OpenBagFlag(); },
          "bags"};
}

Command BagExtractCommand() {
  return {"bag extract",
          "write a bag's IMU and image topics as EuRoC/ASL folders",
          "splinecal bag extract FILE... [--bags FILE,...] --out DIR [--topics T0,T1,...]\n"
          "    [--bag-time header|receive]",
          "Writes the IMU topics (sensor_msgs/Imu) as DIR/imu0/data.csv, imu1, ... and the image\n"
          "topics (sensor_msgs/Image in mono8, mono16, 8UC1, bgr8, rgb8, bgra8, rgba8 and the\n"
          "four bayer encodings; CompressedImage in JPEG or PNG) as DIR/cam0/data.csv and\n"
          "DIR/cam0/data/<t_ns>.png, cam1, ... in 8-bit grey: the folders every other command\n"
          "reads (docs/bags.md says how each encoding becomes grey). Topics are taken in the order\n"
          "--topics gives, by name without it. A message's time is its header stamp, or with\n"
          "--bag-time receive the recording time; a topic whose times go backwards or repeat is\n"
          "refused at its first offending message. result.yaml says which topic became which\n"
          "folder.",
          {{"bags", ""}, {"out", ""}, {"topics", ""}, {"bag_time", ""}},
          &RunBagExtract,
          [] {
            const std::unique_ptr<BagReader> bag = OpenBagFlag();
            ExtractBag(bag.get(), ExtractOptionsFromFlags(), FLAGS_bags, nullptr);
          },
          "bags"};
}

}  // namespace cli
}  // namespace splinecal
