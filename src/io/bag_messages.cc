// ROS 1 serialization (wiki.ros.org/msg, "Serialization"): fields packed little-endian without
// padding, strings and arrays as a uint32 length then the bytes, time as uint32 sec, nsec.
// CDR (OMG CDR as ROS 2 writes it): a 4-byte encapsulation header (00 01: little-endian CDR),
// then fields aligned to their size counted from after that header, strings with their
// terminating NUL counted in the length, time as int32 sec, uint32 nanosec; ROS 2's Header has no
// seq.
#include "splinecal/io/bag_messages.h"

#include <cstring>

#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

class MessageCursor {
 public:
  MessageCursor(const BagTopic& topic, const BagMessage& message)
      : bytes_(message.data), where_(message.where), topic_(topic.name) {
    cdr_ = topic.serialization == BagSerialization::kCdr;
    if (cdr_) {
      if (bytes_.size() < 4) Fail("shorter than its CDR encapsulation header");
      if (bytes_[0] != 0 || bytes_[1] != 1) {
        Fail(StringPrintf("CDR encapsulation %02x %02x is not little-endian CDR (00 01)",
                          static_cast<uint8_t>(bytes_[0]), static_cast<uint8_t>(bytes_[1])));
      }
      pos_ = 4;
    }
  }

  template <typename T>
  T Get(const char* what) {
    Align(sizeof(T));
    Need(sizeof(T), what);
    T value;
    std::memcpy(&value, bytes_.data() + pos_, sizeof(T));
    pos_ += sizeof(T);
    return value;
  }
  std::string_view Bytes(const char* what) {
    const uint32_t length = Get<uint32_t>(what);
    Need(length, what);
    const std::string_view out = bytes_.substr(pos_, length);
    pos_ += length;
    return out;
  }
  std::string String(const char* what) {
    std::string_view text = Bytes(what);
    if (cdr_ && !text.empty() && text.back() == '\0') text.remove_suffix(1);
    return std::string(text);
  }
  // std_msgs/Header: the stamp [ns]; frame_id skipped.
  int64_t HeaderStamp() {
    if (!cdr_) Get<uint32_t>("header seq");
    const int32_t sec = cdr_ ? Get<int32_t>("header stamp") : 0;
    const uint32_t usec = cdr_ ? 0 : Get<uint32_t>("header stamp");
    const uint32_t nsec = Get<uint32_t>("header stamp");
    if (sec < 0) Fail("header stamp is before 1970 (negative seconds)");
    if (nsec >= 1'000'000'000u) Fail(StringPrintf("header stamp has %u nanoseconds", nsec));
    String("header frame_id");
    return (cdr_ ? int64_t{sec} : int64_t{usec}) * 1'000'000'000 + nsec;
  }
  Eigen::Vector3d Vector3(const char* what) {
    Eigen::Vector3d v;
    for (int i = 0; i < 3; ++i) v[i] = Get<double>(what);
    return v;
  }
  void Skip(int doubles, const char* what) {
    for (int i = 0; i < doubles; ++i) Get<double>(what);
  }
  [[noreturn]] void Fail(const std::string& message) const {
    throw Error(where_ + ": " + topic_ + ": " + message);
  }

 private:
  void Align(size_t size) {
    if (cdr_) {
      const size_t misalignment = (pos_ - 4) % size;
      if (misalignment != 0) pos_ += size - misalignment;
    }
  }
  void Need(size_t count, const char* what) const {
    if (pos_ > bytes_.size() || count > bytes_.size() - pos_) {
      Fail(StringPrintf("message ends inside its %s (%zu bytes)", what, bytes_.size()));
    }
  }

  std::string_view bytes_;
  const std::string& where_;
  const std::string& topic_;
  bool cdr_ = false;
  size_t pos_ = 0;
};

}  // namespace

BagMessageKind KindOfType(const std::string& type) {
  if (type == "sensor_msgs/Imu" || type == "sensor_msgs/msg/Imu") return BagMessageKind::kImu;
  if (type == "sensor_msgs/Image" || type == "sensor_msgs/msg/Image") {
    return BagMessageKind::kImage;
  }
  if (type == "sensor_msgs/CompressedImage" || type == "sensor_msgs/msg/CompressedImage") {
    return BagMessageKind::kCompressedImage;
  }
  return BagMessageKind::kOther;
}

ImuMessage ParseImuMessage(const BagTopic& topic, const BagMessage& message) {
  MessageCursor cursor(topic, message);
  ImuMessage imu;
  imu.stamp_ns = cursor.HeaderStamp();
  cursor.Skip(4 + 9, "orientation");
  imu.gyro = cursor.Vector3("angular_velocity");
  cursor.Skip(9, "angular_velocity_covariance");
  imu.accel = cursor.Vector3("linear_acceleration");
  cursor.Skip(9, "linear_acceleration_covariance");
  return imu;
}

ImageMessage ParseImageMessage(const BagTopic& topic, const BagMessage& message) {
  MessageCursor cursor(topic, message);
  ImageMessage image;
  image.stamp_ns = cursor.HeaderStamp();
  if (KindOfType(topic.type) == BagMessageKind::kCompressedImage) {
    image.compressed = true;
    image.encoding = cursor.String("format");
    image.data = cursor.Bytes("data");
    return image;
  }
  image.height = cursor.Get<uint32_t>("height");
  image.width = cursor.Get<uint32_t>("width");
  image.encoding = cursor.String("encoding");
  image.big_endian = cursor.Get<uint8_t>("is_bigendian") != 0;
  image.step = cursor.Get<uint32_t>("step");
  image.data = cursor.Bytes("data");
  if (static_cast<uint64_t>(image.step) * image.height > image.data.size()) {
    cursor.Fail(StringPrintf("image of %u rows of %u bytes has only %zu data bytes", image.height,
                             image.step, image.data.size()));
  }
  return image;
}

BagTime ParseBagTime(const std::string& text) {
  if (text == "header") return BagTime::kHeader;
  if (text == "receive") return BagTime::kReceive;
  throw Error("--bag-time: '" + text + "' is not 'header' or 'receive'");
}

int64_t BagStamps::Stamp(const BagTopic& topic, const BagMessage& message,
                         int64_t header_stamp_ns) {
  const int64_t t = time_ == BagTime::kHeader ? header_stamp_ns : message.receive_time_ns;
  int64_t& last = last_.at(message.topic);
  if (last != kNone && t <= last) {
    throw Error(message.where + ": topic " + topic.name + ": " +
                (time_ == BagTime::kHeader ? "header stamp " : "receive time ") +
                std::to_string(t) + " ns " + (t == last ? "repeats" : "is before") +
                " the previous message's " + std::to_string(last) +
                (time_ == BagTime::kHeader ? " (--bag-time receive takes the recording time)"
                                           : ""));
  }
  last = t;
  return t;
}

}  // namespace splinecal
