// Reading ROS recordings without ROS (docs/bags.md): ROS 1 bags (format 2.0), ROS 2 MCAP files
// and ROS 2 sqlite3 bags (.db3 files listed in metadata.yaml).
//
// A BagReader streams the messages of the chosen topics in recording-time order, one at a time,
// without loading the bag: it first collects where each message is (the bag's index, or one pass
// over the file when the index is missing) and then decompresses one chunk at a time as the
// messages in it are asked for. Memory is the message index (about 32 bytes a message) plus a few
// decompressed chunks, so a 10 GB bag streams in a few tens of MB.
//
// Message bytes are handed out raw, in the bag's serialization (ROS 1 or CDR); io/bag_messages.h
// parses the message types splinecal reads.
#ifndef SPLINECAL_IO_BAG_READER_H_
#define SPLINECAL_IO_BAG_READER_H_

#include <cstdint>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace splinecal {

// How a bag serializes its messages.
enum class BagSerialization {
  kRos1,  // ROS 1's little-endian packing, no alignment
  kCdr,   // ROS 2's CDR (OMG DDS-XTypes), with its 4-byte encapsulation header
};

struct BagTopic {
  std::string name;  // "/imu0"
  std::string type;  // "sensor_msgs/Imu" (ROS 2's "sensor_msgs/msg/Imu" is kept as written)
  BagSerialization serialization = BagSerialization::kRos1;
  int64_t message_count = 0;
  int64_t first_time_ns = 0;  // recording (receive) time of its first and last message
  int64_t last_time_ns = 0;
  int64_t max_gap_ns = 0;     // longest interval between two of its messages (recording time)
};

// One message. `data` stays valid until the next call of BagReader::Next.
struct BagMessage {
  int topic = 0;               // index into BagReader::topics()
  int64_t receive_time_ns = 0; // the recording time (ROS 1 record time, MCAP log_time, .db3)
  std::string_view data;       // serialized message
  std::string where;           // file and position, for error messages ("a.bag:offset 4096")
};

class BagReader {
 public:
  virtual ~BagReader() = default;

  // Every topic of the recording with its message count (all files together).
  const std::vector<BagTopic>& topics() const { return topics_; }
  // The index of `name` in topics(), -1 when absent.
  int FindTopic(const std::string& name) const;
  // Problems the reader worked around (an unindexed bag read by a linear scan).
  const std::vector<std::string>& warnings() const { return warnings_; }
  // Total bytes of the bag's files.
  int64_t file_bytes() const { return file_bytes_; }
  // The format's name: "ROS 1 bag 2.0", "MCAP", "ROS 2 sqlite3".
  virtual std::string format() const = 0;

  // Restricts Next() to these topics (indices into topics()); all topics by default. Restarts the
  // iteration.
  virtual void SelectTopics(const std::vector<int>& topics) = 0;
  // The next message of the selected topics in recording-time order (ties in file order); false
  // at the end. Throws splinecal::Error for a damaged bag (a truncated or corrupt chunk).
  virtual bool Next(BagMessage* message) = 0;

 protected:
  std::vector<BagTopic> topics_;
  std::vector<std::string> warnings_;
  int64_t file_bytes_ = 0;
};

// Opens a recording given as one or more paths, told apart by their contents:
// - ROS 1 bags ("#ROSBAG V2.0"); several (a split recording, foo_0.bag foo_1.bag) read as one;
// - MCAP files (one);
// - a ROS 2 sqlite3 bag: its folder, its metadata.yaml, or its .db3 files (given without
//   metadata.yaml, the .db3 files given are read as one recording).
// Throws splinecal::Error naming the file for a missing or unreadable file, an unknown format,
// a damaged header or index, a .db3 listed in metadata.yaml that is missing, or two topics of
// one name with different types in a split recording.
std::unique_ptr<BagReader> OpenBag(const std::vector<std::string>& paths);

namespace internal {
// Counts, time range and longest gap of every topic from its messages' recording times, given
// in time order (each reader calls it once its index is sorted).
void AddTopicStatistics(int topic, int64_t time_ns, std::vector<BagTopic>* topics);
}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_IO_BAG_READER_H_
