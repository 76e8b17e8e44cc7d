#include "splinecal/detect/bag_extract.h"

#include <algorithm>
#include <sstream>

#include "splinecal/detect/bag_image.h"
#include "splinecal/error.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/yaml_writer.h"

namespace splinecal {

std::vector<ExtractedTopic> ChooseExtractedTopics(const BagReader& bag,
                                                  const BagExtractOptions& options,
                                                  const std::string& name) {
  std::vector<int> chosen;
  std::string available;
  for (const BagTopic& topic : bag.topics()) {
    if (KindOfType(topic.type) != BagMessageKind::kOther) {
      available += (available.empty() ? "" : ", ") + topic.name;
    }
  }
  if (available.empty()) available = "none";
  for (const std::string& topic_name : options.topics) {
    const int topic = bag.FindTopic(topic_name);
    if (topic < 0) {
      throw Error("--topics: " + topic_name +
                  " is not in the recording (its IMU and image topics: " + available + ")");
    }
    if (KindOfType(bag.topics()[topic].type) == BagMessageKind::kOther) {
      throw Error("--topics: " + topic_name + " is a " + bag.topics()[topic].type +
                  ", not an IMU or image topic (sensor_msgs/Imu, Image, CompressedImage)");
    }
    if (std::find(chosen.begin(), chosen.end(), topic) == chosen.end()) chosen.push_back(topic);
  }
  if (options.topics.empty()) {
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
    throw Error(name + ": no sensor_msgs/Imu, Image or CompressedImage topic to extract");
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

std::vector<ExtractedTopic> ExtractBag(BagReader* bag, const BagExtractOptions& options,
                                       const std::string& name, OutputDir* output) {
  std::vector<ExtractedTopic> topics = ChooseExtractedTopics(*bag, options, name);
  std::vector<int> selected;
  std::vector<int> slot(bag->topics().size(), -1);
  for (size_t i = 0; i < topics.size(); ++i) {
    selected.push_back(topics[i].topic);
    slot[topics[i].topic] = static_cast<int>(i);
  }
  bag->SelectTopics(selected);
  BagStamps stamps(options.time, bag->topics().size());
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
      const std::string file = std::to_string(t_ns) + ".png";
      out.frames_csv += std::to_string(t_ns) + "," + file + "\n";
      if (output != nullptr) {
        output->WriteFile(out.folder + "/data/" + file, EncodeGrayPng(gray.view()));
      }
    }
    if (out.messages++ == 0) out.first_t_ns = t_ns;
    out.last_t_ns = t_ns;
    if (++done % 1000 == 0 && options.progress) options.progress(done);
  }
  if (output != nullptr) {
    for (const ExtractedTopic& topic : topics) {
      if (!topic.imu.empty() || topic.frames_csv.empty()) {
        std::ostringstream csv;
        WriteEurocImu(topic.imu, &csv);
        output->WriteFile(topic.folder + "/data.csv", csv.str());
      } else {
        output->WriteFile(topic.folder + "/data.csv", topic.frames_csv);
      }
    }
  }
  return topics;
}

std::string BagExtractResultYaml(const BagReader& bag, const std::vector<std::string>& paths,
                                 const std::string& bag_time,
                                 const std::vector<ExtractedTopic>& topics) {
  YamlWriter yaml;
  yaml.Comment("splinecal bag extract: a recording's IMU and image topics as EuRoC/ASL folders "
               "(docs/bags.md)");
  yaml.StringList("bags", paths);
  yaml.Scalar("format", bag.format());
  yaml.Scalar("bag_time", bag_time);
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

}  // namespace splinecal
