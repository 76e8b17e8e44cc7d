#include "splinecal/detect/detect_bag.h"

#include <algorithm>
#include <memory>
#include <utility>

#include "detect_frames.h"
#include "splinecal/detect/bag_image.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_reader.h"

namespace splinecal {
namespace {

bool IsImageTopic(const BagTopic& topic) {
  const BagMessageKind kind = KindOfType(topic.type);
  return kind == BagMessageKind::kImage || kind == BagMessageKind::kCompressedImage;
}

// The recording's image topics, "a, b" ("none" without any).
std::string ImageTopics(const BagReader& bag) {
  std::string names;
  for (const BagTopic& topic : bag.topics()) {
    if (IsImageTopic(topic)) names += (names.empty() ? "" : ", ") + topic.name;
  }
  return names.empty() ? "none" : names;
}

// The messages of the chosen topics in recording order. Take copies one message out of the bag
// (the reader's buffer is reused by the next Take) and checks its time; the workers decode it.
class BagFrames : public internal::FrameSource {
 public:
  BagFrames(BagReader* bag, std::vector<int> topics, BagTime time)
      : bag_(bag),
        topics_(std::move(topics)),
        cam_of_topic_(bag->topics().size(), -1),
        taken_(topics_.size(), 0),
        stamps_(time, bag->topics().size()) {
    for (size_t cam = 0; cam < topics_.size(); ++cam) cam_of_topic_[topics_[cam]] = int(cam);
    bag_->SelectTopics(topics_);
  }

  bool Take(internal::FrameJob* job) override {
    BagMessage message;
    if (!bag_->Next(&message)) return false;
    const BagTopic& topic = bag_->topics()[message.topic];
    job->cam = cam_of_topic_[message.topic];
    job->index = taken_[job->cam]++;
    job->bytes.assign(message.data.data(), message.data.size());
    const ImageMessage image = ParseImageMessage(topic, message);
    job->frame.t_ns = stamps_.Stamp(topic, message, image.stamp_ns);
    job->frame.path.clear();
    job->frame.origin = message.where + ": " + topic.name;
    return true;
  }

  GrayImage Decode(const internal::FrameJob& job) const override {
    const int topic = topics_[job.cam];
    BagMessage message;
    message.topic = topic;
    message.data = job.bytes;
    message.where = job.frame.origin;
    return BagImageToGray(ParseImageMessage(bag_->topics()[topic], message), job.frame.origin);
  }

 private:
  BagReader* bag_;
  std::vector<int> topics_;
  std::vector<int> cam_of_topic_;
  std::vector<int64_t> taken_;
  BagStamps stamps_;
};

// The sizes of the topic's first readable frames (at most 5), as DetectFolders finds a folder's.
std::vector<std::pair<int, int>> FirstSizes(BagReader* bag, int topic) {
  bag->SelectTopics({topic});
  std::vector<std::pair<int, int>> sizes;
  BagMessage message;
  while (sizes.size() < 5 && bag->Next(&message)) {
    try {
      const GrayImage image = BagImageToGray(
          ParseImageMessage(bag->topics()[topic], message), message.where);
      sizes.emplace_back(image.width, image.height);
    } catch (const Error&) {
      // The workers read it again and report the problem with the frame.
    }
  }
  return sizes;
}

std::string RecordingName(const BagImageSource& source) {
  std::string name;
  for (const std::string& path : source.paths) name += (name.empty() ? "" : ",") + path;
  return name;
}

// The topics' indices in the recording, in camera order; throws for a bad topic.
std::vector<int> ImageTopicIndices(const BagReader& bag, const BagImageSource& source) {
  if (source.topics.empty()) throw Error("--image-topics: no topic given");
  std::vector<int> topics;
  for (const std::string& topic_name : source.topics) {
    const int topic = bag.FindTopic(topic_name);
    if (topic < 0) {
      throw Error("--image-topics " + topic_name + ": not in " + RecordingName(source) +
                  " (its image topics: " + ImageTopics(bag) + ")");
    }
    if (!IsImageTopic(bag.topics()[topic])) {
      throw Error("--image-topics " + topic_name + ": a " + bag.topics()[topic].type +
                  " topic, not sensor_msgs/Image or CompressedImage (the recording's image "
                  "topics: " + ImageTopics(bag) + ")");
    }
    if (std::find(topics.begin(), topics.end(), topic) != topics.end()) {
      throw Error("--image-topics " + topic_name + ": given twice");
    }
    topics.push_back(topic);
  }
  return topics;
}

}  // namespace

void CheckBagImageSource(const BagImageSource& source) {
  ImageTopicIndices(*OpenBag(source.paths), source);
}

DetectFoldersResult DetectBag(const BagImageSource& source,
                              const CalibrationTarget& target,
                              const DetectFoldersOptions& options) {
  const std::unique_ptr<BagReader> bag = OpenBag(source.paths);
  const std::vector<int> topics = ImageTopicIndices(*bag, source);
  std::vector<CameraDetectionSummary> cameras;
  for (size_t cam = 0; cam < topics.size(); ++cam) {
    CameraDetectionSummary summary;
    summary.cam_id = static_cast<int>(cam);
    summary.dir = RecordingName(source) + ":" + source.topics[cam];
    summary.images_listed = bag->topics()[topics[cam]].message_count;
    internal::ChooseResolution(FirstSizes(bag.get(), topics[cam]), &summary);
    cameras.push_back(summary);
  }
  std::vector<std::string> warnings = bag->warnings();
  BagFrames frames(bag.get(), topics, source.time);
  return internal::DetectFrames(&frames, std::move(cameras), std::move(warnings), target,
                                options);
}

}  // namespace splinecal
