// The ROS messages splinecal reads from bags (docs/bags.md), parsed from their ROS 1 or CDR
// bytes (io/bag_reader.h) without ROS:
//   sensor_msgs/Imu              header, orientation (+cov), angular_velocity (+cov),
//                                linear_acceleration (+cov)
//   sensor_msgs/Image            header, height, width, encoding, is_bigendian, step, data
//   sensor_msgs/CompressedImage  header, format, data
// Pixels stay raw here: turning them into the detector's 8-bit grey is detect/bag_image.h's job
// (the core library has no image code).
#ifndef SPLINECAL_IO_BAG_MESSAGES_H_
#define SPLINECAL_IO_BAG_MESSAGES_H_

#include <climits>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Core>

#include "splinecal/io/bag_reader.h"

namespace splinecal {

enum class BagMessageKind { kImu, kImage, kCompressedImage, kOther };
// By type name, ROS 1 ("sensor_msgs/Imu") or ROS 2 ("sensor_msgs/msg/Imu") spelling.
BagMessageKind KindOfType(const std::string& type);

struct ImuMessage {
  int64_t stamp_ns = 0;  // header stamp
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // angular_velocity [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // linear_acceleration [m/s^2]
};

// A sensor_msgs/Image or CompressedImage; `data` views into the message's bytes.
struct ImageMessage {
  int64_t stamp_ns = 0;
  bool compressed = false;
  // Image only.
  uint32_t width = 0;
  uint32_t height = 0;
  uint32_t step = 0;  // bytes per row
  bool big_endian = false;
  // Image: its encoding ("mono8", "bayer_rggb8", ...); CompressedImage: its format ("jpeg",
  // "png", or ROS's longer "mono8; jpeg compressed mono8").
  std::string encoding;
  std::string_view data;
};

// Parse `message` of topic `topic`. Throw splinecal::Error naming message.where for bytes that
// end early, a header stamp before 1970 (negative), a CDR message that is not little-endian CDR,
// or an Image whose data is shorter than height * step.
ImuMessage ParseImuMessage(const BagTopic& topic, const BagMessage& message);
ImageMessage ParseImageMessage(const BagTopic& topic, const BagMessage& message);

// Which clock a message's time comes from: its header stamp (the sensor's time, as Kalibr takes
// it; the default) or the time the recorder received it.
enum class BagTime { kHeader, kReceive };
// "header" or "receive"; throws splinecal::Error naming --bag-time otherwise.
BagTime ParseBagTime(const std::string& text);

// The times of a stream of messages, checked to increase strictly per topic: a topic whose stamps
// go backwards or repeat is refused with its first offending message.
class BagStamps {
 public:
  BagStamps(BagTime time, size_t topic_count) : time_(time), last_(topic_count, kNone) {}
  // The time of `message` (its header stamp `header_stamp_ns` or its receive time); throws
  // splinecal::Error "<where>: topic T: time t is not after the previous message's t0" when it
  // does not increase.
  int64_t Stamp(const BagTopic& topic, const BagMessage& message, int64_t header_stamp_ns);

 private:
  static constexpr int64_t kNone = INT64_MIN;
  BagTime time_;
  std::vector<int64_t> last_;
};

}  // namespace splinecal

#endif  // SPLINECAL_IO_BAG_MESSAGES_H_
