// `splinecal bag info` and `splinecal bag extract`: ROS 1 bags, MCAP files and rosbag2 sqlite3
// recordings (io/bag_reader.h, docs/bags.md) listed like `rosbag info`, and turned into the
// EuRoC/ASL folders every other command reads.
#include <gflags/gflags.h>

#include <algorithm>
#include <cinttypes>
#include <cstdio>
#include <memory>
#include <sstream>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/detect/bag_image.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/yaml_writer.h"
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

// One extracted topic and the folder it becomes.
struct ExtractedTopic {
  int topic = 0;
  std::string folder;  // "imu0", "cam0"
  std::vector<ImuSample> imu;
  std::string frames_csv;
  int64_t messages = 0;
  int64_t first_t_ns = 0;  // as written (header stamp or receive time)
  int64_t last_t_ns = 0;
};

// result.yaml of `bag extract` (docs/conventions.md, "Command line"): which topic became which
// folder, with its count and time range.
std::string ExtractResultYaml(const BagReader& bag, const std::vector<ExtractedTopic>& topics) {
  YamlWriter yaml;
  yaml.Comment("splinecal bag extract: a recording's IMU and image topics as EuRoC/ASL folders "
               "(docs/bags.md)");
  yaml.StringList("bags", ListFlag("bags", FLAGS_bags));
  yaml.Scalar("format", bag.format());
  yaml.Scalar("bag_time", FLAGS_bag_time);
  yaml.BeginMap("folders");
  for (const ExtractedTopic& topic : topics) {
    yaml.BeginMap(topic.folder);
    yaml.Scalar("topic", bag.topics()[topic.topic].name);
    yaml.Scalar("type", bag.topics()[topic.topic].type);
    yaml.Scalar("messages", topic.messages);
    yaml.Scalar("first_t_ns", topic.first_t_ns);
    yaml.Scalar("last_t_ns", topic.last_t_ns);
    yaml.EndMap();
  }
  yaml.EndMap();
  yaml.StringList("warnings", bag.warnings());
  return yaml.str();
}

// The topics --topics names (all readable ones when empty), each with its folder: IMU topics
// become imu0, imu1, ..., image topics cam0, cam1, ... in the order given (by name when all).
std::vector<ExtractedTopic> ExtractedTopics(const BagReader& bag) {
  std::vector<int> chosen;
  const std::vector<std::string> names = ListFlag("topics", FLAGS_topics);
  std::string available;
  for (const BagTopic& topic : bag.topics()) {
    if (KindOfType(topic.type) != BagMessageKind::kOther) {
      available += (available.empty() ? "" : ", ") + topic.name;
    }
  }
  if (available.empty()) available = "none";
  for (const std::string& name : names) {
    const int topic = bag.FindTopic(name);
    if (topic < 0) {
      throw Error("--topics: " + name + " is not in the recording (its IMU and image topics: " +
                  available + ")");
    }
    if (KindOfType(bag.topics()[topic].type) == BagMessageKind::kOther) {
      throw Error("--topics: " + name + " is a " + bag.topics()[topic].type +
                  ", not an IMU or image topic (sensor_msgs/Imu, Image, CompressedImage)");
    }
    if (std::find(chosen.begin(), chosen.end(), topic) == chosen.end()) chosen.push_back(topic);
  }
  if (names.empty()) {
    for (size_t i = 0; i < bag.topics().size(); ++i) {
      if (KindOfType(bag.topics()[i].type) != BagMessageKind::kOther) {
        chosen.push_back(static_cast<int>(i));
      }
    }
    std::sort(chosen.begin(), chosen.end(), [&bag](int a, int b) {
      return bag.topics()[a].name < bag.topics()[b].name;
    });
  }
  if (chosen.empty()) {
    throw Error(FLAGS_bags + ": no sensor_msgs/Imu, Image or CompressedImage topic to extract");
  }
  std::vector<ExtractedTopic> topics;
  int imus = 0;
  int cameras = 0;
  for (const int topic : chosen) {
    const bool imu = KindOfType(bag.topics()[topic].type) == BagMessageKind::kImu;
    ExtractedTopic extracted;
    extracted.topic = topic;
    extracted.folder = imu ? "imu" + std::to_string(imus++) : "cam" + std::to_string(cameras++);
    if (!imu) extracted.frames_csv = "#timestamp [ns],filename\n";
    topics.push_back(std::move(extracted));
  }
  return topics;
}

// Reads every message of the extracted topics; with `output`, stages the folders in it.
std::vector<ExtractedTopic> Extract(BagReader* bag, OutputDir* output) {
  std::vector<ExtractedTopic> topics = ExtractedTopics(*bag);
  const BagTime time = ParseBagTime(FLAGS_bag_time);
  std::vector<int> selected;
  std::vector<int> slot(bag->topics().size(), -1);
  for (size_t i = 0; i < topics.size(); ++i) {
    selected.push_back(topics[i].topic);
    slot[topics[i].topic] = static_cast<int>(i);
  }
  bag->SelectTopics(selected);
  BagStamps stamps(time, bag->topics().size());
  BagMessage message;
  int64_t done = 0;
  while (bag->Next(&message)) {
    const BagTopic& topic = bag->topics()[message.topic];
    ExtractedTopic& out = topics[slot[message.topic]];
    int64_t t_ns;
    if (KindOfType(topic.type) == BagMessageKind::kImu) {
      const ImuMessage imu = ParseImuMessage(topic, message);
      t_ns = stamps.Stamp(topic, message, imu.stamp_ns);
      out.imu.push_back({t_ns, imu.gyro, imu.accel});
    } else {
      const ImageMessage image = ParseImageMessage(topic, message);
      t_ns = stamps.Stamp(topic, message, image.stamp_ns);
      const GrayImage gray = BagImageToGray(image, message.where + ": " + topic.name);
      const std::string name = std::to_string(t_ns) + ".png";
      out.frames_csv += std::to_string(t_ns) + "," + name + "\n";
      if (output != nullptr) {
        output->WriteFile(out.folder + "/data/" + name, EncodeGrayPng(gray.view()));
      }
    }
    if (out.messages++ == 0) out.first_t_ns = t_ns;
    out.last_t_ns = t_ns;
    if (++done % 1000 == 0) Progress(StringPrintf("bag extract: %lld messages", (long long)done));
  }
  return topics;
}

int RunBagExtract() {
  const std::unique_ptr<BagReader> bag = OpenBagFlag();
  PrintWarnings(*bag);
  ExtractedTopics(*bag);  // refuses a bad --topics before the output folder is made
  ParseBagTime(FLAGS_bag_time);
  OutputDir output(RequiredFlag("out", FLAGS_out));
  const std::vector<ExtractedTopic> topics = Extract(bag.get(), &output);
  for (const ExtractedTopic& topic : topics) {
    if (!topic.imu.empty() || topic.frames_csv.empty()) {
      std::ostringstream csv;
      WriteEurocImu(topic.imu, &csv);
      output.WriteFile(topic.folder + "/data.csv", csv.str());
    } else {
      output.WriteFile(topic.folder + "/data.csv", topic.frames_csv);
    }
    std::printf("%-5s <- %s (%lld messages, %s)\n", topic.folder.c_str(),
                bag->topics()[topic.topic].name.c_str(), static_cast<long long>(topic.messages),
                bag->topics()[topic.topic].type.c_str());
  }
  output.WriteFile("result.yaml", ExtractResultYaml(*bag, topics));
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
            Extract(bag.get(), nullptr);
          },
          "bags"};
}

}  // namespace cli
}  // namespace splinecal
