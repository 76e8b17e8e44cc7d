// The bag readers (io/bag_reader.h, io/bag_messages.h) on the fixtures of data/bags/, written by
// independent writers (scripts/make_bag_fixtures.sh: python3-rosbag, @mcap/core with
// @foxglove/rosmsg2-serialization): every IMU sample equals the EuRoC CSV it was written from,
// exactly; images equal the crop of the real frame they came from; broken bags are refused with
// a message naming the file, never a crash.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <random>
#include <string>
#include <vector>

#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/euroc.h"
#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::AllOf;
using ::testing::HasSubstr;

std::string Bag(const std::string& name) { return testing::BundledDataPath("bags/" + name); }

// What the fixture script wrote (make_mcap_fixtures.mjs): the first 100 IMU rows, received 1 ms
// after their stamp; a 96 x 64 crop at (328, 208) of each real frame, stamped as IMU row 50 and
// received 5 ms later.
constexpr int kImuSamples = 100;
constexpr int64_t kImuReceiveDelayNs = 1'000'000;
constexpr int64_t kImageReceiveDelayNs = 5'000'000;
constexpr int kCropX = 328, kCropY = 208, kCropW = 96, kCropH = 64;

std::vector<ImuSample> ExpectedImu() {
  std::vector<ImuSample> imu = ReadEurocImu(testing::BundledDataPath("euroc_v1_01_easy_20s/imu0.csv"));
  imu.resize(kImuSamples);
  return imu;
}

std::vector<uint8_t> ExpectedCrop(int cam) {
  const GrayImage frame = ReadGrayImage(testing::BundledDataPath(
      "euroc_april_frames/cam" + std::to_string(cam) + "/data/1403709395937837056.png"));
  std::vector<uint8_t> crop;
  for (int y = kCropY; y < kCropY + kCropH; ++y) {
    for (int x = kCropX; x < kCropX + kCropW; ++x) crop.push_back(frame.pixels[y * frame.width + x]);
  }
  return crop;
}

struct Fixture {
  std::vector<std::string> files;
  bool expect_warning;
};

// For test names in failures (and so that GoogleTest does not print the struct's padding).
void PrintTo(const Fixture& fixture, std::ostream* out) { *out << fixture.files[0]; }

class BagFixtureTest : public ::testing::TestWithParam<Fixture> {};

TEST_P(BagFixtureTest, ImuSamplesAndImagesEqualTheirSourcesExactly) {
  std::vector<std::string> paths;
  for (const std::string& file : GetParam().files) paths.push_back(Bag(file));
  const std::unique_ptr<BagReader> bag = OpenBag(paths);
  EXPECT_EQ(bag->warnings().size(), GetParam().expect_warning ? 1u : 0u);
  const int imu_topic = bag->FindTopic("/imu0");
  ASSERT_GE(imu_topic, 0);
  EXPECT_EQ(bag->topics()[imu_topic].message_count, kImuSamples);
  EXPECT_EQ(KindOfType(bag->topics()[imu_topic].type), BagMessageKind::kImu);
  const int other = bag->FindTopic("/other");
  ASSERT_GE(other, 0);
  EXPECT_EQ(KindOfType(bag->topics()[other].type), BagMessageKind::kOther);

  const std::vector<ImuSample> expected = ExpectedImu();
  std::vector<int> selected = {imu_topic, bag->FindTopic("/cam0/image_raw"),
                               bag->FindTopic("/cam1/image_raw")};
  ASSERT_GE(selected[1], 0);
  ASSERT_GE(selected[2], 0);
  bag->SelectTopics(selected);
  BagMessage message;
  int imu = 0;
  int images = 0;
  int64_t last_receive = 0;
  while (bag->Next(&message)) {
    EXPECT_GE(message.receive_time_ns, last_receive) << message.where;  // recording-time order
    last_receive = message.receive_time_ns;
    const BagTopic& topic = bag->topics()[message.topic];
    if (message.topic == imu_topic) {
      ASSERT_LT(imu, kImuSamples);
      const ImuMessage sample = ParseImuMessage(topic, message);
      EXPECT_EQ(sample.stamp_ns, expected[imu].t_ns);
      EXPECT_EQ(message.receive_time_ns, expected[imu].t_ns + kImuReceiveDelayNs);
      // Exact: the CSV's decimal text, the writers' float64 and ours are the same double.
      EXPECT_EQ(sample.gyro, expected[imu].gyro) << imu;
      EXPECT_EQ(sample.accel, expected[imu].accel) << imu;
      ++imu;
    } else {
      const ImageMessage image = ParseImageMessage(topic, message);
      EXPECT_EQ(image.stamp_ns, expected[50].t_ns);
      EXPECT_EQ(message.receive_time_ns, expected[50].t_ns + kImageReceiveDelayNs);
      EXPECT_EQ(image.encoding, "mono8");
      EXPECT_EQ(image.width, static_cast<uint32_t>(kCropW));
      EXPECT_EQ(image.height, static_cast<uint32_t>(kCropH));
      EXPECT_EQ(image.step, static_cast<uint32_t>(kCropW));
      const int cam = topic.name == "/cam0/image_raw" ? 0 : 1;
      EXPECT_EQ(std::vector<uint8_t>(image.data.begin(), image.data.end()), ExpectedCrop(cam));
      ++images;
    }
  }
  EXPECT_EQ(imu, kImuSamples);
  EXPECT_EQ(images, 2);
}

INSTANTIATE_TEST_SUITE_P(
    Fixtures, BagFixtureTest,
    ::testing::Values(Fixture{{"ros1_none.bag"}, false}, Fixture{{"ros1_bz2.bag"}, false},
                      Fixture{{"ros1_lz4.bag"}, false}, Fixture{{"ros1_unindexed.bag"}, true},
                      Fixture{{"ros1_split_0.bag", "ros1_split_1.bag"}, false},
                      Fixture{{"mcap_none.mcap"}, false}, Fixture{{"mcap_zstd.mcap"}, false},
                      Fixture{{"mcap_lz4.mcap"}, false}, Fixture{{"mcap_unindexed.mcap"}, true},
                      Fixture{{"mcap_unchunked.mcap"}, false},
                      Fixture{{"rosbag2_db3"}, false},
                      Fixture{{"rosbag2_db3/metadata.yaml"}, false},
                      Fixture{{"rosbag2_db3/rosbag2_db3_0.db3", "rosbag2_db3/rosbag2_db3_1.db3"},
                              false}));

std::string ReadBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

std::string WriteBytes(const testing::TempDir& dir, const std::string& name,
                       const std::string& bytes) {
  std::ofstream(dir.File(name), std::ios::binary) << bytes;
  return dir.File(name);
}

// Opens and reads every message; returns the error's text ("" when none).
std::string ReadAll(const std::vector<std::string>& paths) {
  try {
    const std::unique_ptr<BagReader> bag = OpenBag(paths);
    BagMessage message;
    while (bag->Next(&message)) {
    }
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(BrokenBagTest, Ros1TruncatedInAChunk) {
  const testing::TempDir dir;
  const std::string bytes = ReadBytes(Bag("ros1_lz4.bag"));
  const std::string path = WriteBytes(dir, "cut.bag", bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(ReadAll({path}), AllOf(HasSubstr(path), HasSubstr("truncated")));
}

// The first chunk's "size" header field (9 bytes: "size=" and a uint32) set one too large.
std::string WithWrongChunkSize(std::string bytes) {
  const size_t field = bytes.find(std::string("\x09\0\0\0size=", 9));
  EXPECT_NE(field, std::string::npos);
  bytes[field + 9] = static_cast<char>(bytes[field + 9] + 1);
  return bytes;
}

TEST(BrokenBagTest, Ros1ChunkWithAWrongSize) {
  const testing::TempDir dir;
  for (const char* name : {"ros1_none.bag", "ros1_bz2.bag", "ros1_lz4.bag"}) {
    const std::string path = WriteBytes(dir, name, WithWrongChunkSize(ReadBytes(Bag(name))));
    EXPECT_THAT(ReadAll({path}), AllOf(HasSubstr(path), HasSubstr("header says"))) << name;
  }
}

TEST(BrokenBagTest, McapBadChunkCrc) {
  const testing::TempDir dir;
  std::string bytes = ReadBytes(Bag("mcap_none.mcap"));
  // The first chunk (op 0x06) follows the header record; its records start 40 bytes into its
  // content (start, end, size, CRC, compression "" and the records' length).
  uint64_t header_length;
  std::memcpy(&header_length, bytes.data() + 9, 8);
  const size_t chunk = 8 + 9 + header_length;
  ASSERT_EQ(bytes[chunk], 0x06);
  bytes[chunk + 9 + 40 + 20] ^= 0x01;
  const std::string path = WriteBytes(dir, "crc.mcap", bytes);
  EXPECT_THAT(ReadAll({path}), AllOf(HasSubstr(path), HasSubstr("fails its CRC")));
}

TEST(BrokenBagTest, McapTruncated) {
  const testing::TempDir dir;
  const std::string bytes = ReadBytes(Bag("mcap_zstd.mcap"));
  const std::string path = WriteBytes(dir, "cut.mcap", bytes.substr(0, bytes.size() / 2));
  EXPECT_THAT(ReadAll({path}), AllOf(HasSubstr(path), HasSubstr("truncated")));
}

TEST(BrokenBagTest, Rosbag2MissingDb3) {
  const testing::TempDir dir;
  std::filesystem::create_directories(dir.File("rec"));
  std::filesystem::copy(Bag("rosbag2_db3/metadata.yaml"), dir.File("rec/metadata.yaml"));
  std::filesystem::copy(Bag("rosbag2_db3/rosbag2_db3_0.db3"), dir.File("rec/rosbag2_db3_0.db3"));
  EXPECT_THAT(ReadAll({dir.File("rec")}),
              AllOf(HasSubstr("rec/rosbag2_db3_1.db3"), HasSubstr("missing")));
}

TEST(BrokenBagTest, NotABag) {
  const testing::TempDir dir;
  const std::string path = dir.Write("imu.csv", "#t,x\n1,2\n");
  EXPECT_THAT(ReadAll({path}), HasSubstr("not a ROS 1 bag, MCAP file or rosbag2"));
  EXPECT_THAT(ReadAll({dir.File("absent.bag")}), HasSubstr("cannot open"));
}

// Damage anywhere - a header field, an index entry, chunk bytes, a CDR length - is refused with
// splinecal::Error or read (a flipped pixel or IMU digit is valid data), never a crash or another
// exception: 300 seeded byte flips per format, each read whole with every message parsed.
TEST(BrokenBagTest, RandomByteFlipsNeverCrash) {
  const testing::TempDir dir;
  std::mt19937 random(7);
  for (const char* name : {"ros1_lz4.bag", "ros1_unindexed.bag", "mcap_zstd.mcap",
                           "mcap_unindexed.mcap", "mcap_unchunked.mcap"}) {
    const std::string original = ReadBytes(Bag(name));
    int refused = 0;
    for (int trial = 0; trial < 300; ++trial) {
      std::string bytes = original;
      const size_t at = std::uniform_int_distribution<size_t>(0, bytes.size() - 1)(random);
      bytes[at] = static_cast<char>(bytes[at] ^ (1 << (trial % 8)));
      const std::string path = WriteBytes(dir, "flipped", bytes);
      try {
        const std::unique_ptr<BagReader> bag = OpenBag({path});
        BagMessage message;
        while (bag->Next(&message)) {
          const BagTopic& topic = bag->topics()[message.topic];
          if (KindOfType(topic.type) == BagMessageKind::kImu) ParseImuMessage(topic, message);
          if (KindOfType(topic.type) == BagMessageKind::kImage) ParseImageMessage(topic, message);
        }
      } catch (const Error&) {
        ++refused;
      }
    }
    // Some flips must be caught (a chunk's compressed bytes, a record length), or the test
    // would not reach the checks.
    EXPECT_GT(refused, 0) << name;
  }
}

TEST(BagStampsTest, RefusesStampsThatGoBackOrRepeatNamingTheMessage) {
  const BagTopic topic{"/imu0", "sensor_msgs/Imu"};
  BagMessage message;
  message.where = "a.bag: chunk at offset 10, message at 20";
  BagStamps stamps(BagTime::kHeader, 1);
  EXPECT_EQ(stamps.Stamp(topic, message, 100), 100);
  EXPECT_EQ(stamps.Stamp(topic, message, 200), 200);
  try {
    stamps.Stamp(topic, message, 200);
    FAIL() << "a repeated stamp was accepted";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("a.bag: chunk at offset 10, message at 20: topic /imu0: "
                                    "header stamp 200 ns repeats"));
  }
  BagStamps receive(BagTime::kReceive, 1);
  message.receive_time_ns = 50;
  EXPECT_EQ(receive.Stamp(topic, message, 999), 50);
  message.receive_time_ns = 40;
  EXPECT_THROW(receive.Stamp(topic, message, 1000), Error);
  EXPECT_THROW(ParseBagTime("sensor"), Error);
}

TEST(BagMessagesTest, ShortMessageIsRefusedWithItsPlace) {
  const BagTopic topic{"/imu0", "sensor_msgs/Imu", BagSerialization::kCdr};
  BagMessage message;
  const std::string bytes("\0\1\0\0\1\0\0\0", 8);
  message.data = bytes;
  message.where = "x.mcap: message at offset 8";
  try {
    ParseImuMessage(topic, message);
    FAIL() << "a short message was parsed";
  } catch (const Error& e) {
    EXPECT_THAT(e.what(), HasSubstr("x.mcap: message at offset 8: /imu0: message ends inside"));
  }
}

}  // namespace
}  // namespace splinecal
