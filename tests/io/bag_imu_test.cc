// IMU samples from a bag topic (io/bag_imu.h) against the rows the fixtures were written from
// (scripts/fixtures/make_mcap_fixtures.mjs: the first 100 rows of the bundled EuRoC IMU, received
// 1 ms after their header stamp), in every format; the static reader against the CSV one.
#include "splinecal/io/bag_imu.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <string>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/static_recording.h"
#include "testing/paths.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

constexpr int kImuSamples = 100;
constexpr int64_t kImuReceiveDelayNs = 1'000'000;

std::string Bag(const std::string& name) { return testing::BundledDataPath("bags/" + name); }

std::vector<ImuSample> ExpectedImu() {
  std::vector<ImuSample> imu =
      ReadEurocImu(testing::BundledDataPath("euroc_v1_01_easy_20s/imu0.csv"));
  imu.resize(kImuSamples);
  return imu;
}

BagImuSource Source(std::vector<std::string> files, BagTime time = BagTime::kHeader) {
  BagImuSource source;
  for (std::string& file : files) file = Bag(file);
  source.paths = files;
  source.topic = "/imu0";
  source.time = time;
  return source;
}

// Exact equality: the bags hold the CSV's doubles, written by independent writers.
void ExpectSameSamples(const std::vector<ImuSample>& a, const std::vector<ImuSample>& b,
                       int64_t time_offset_ns = 0) {
  ASSERT_EQ(a.size(), b.size());
  for (size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].t_ns, b[i].t_ns + time_offset_ns) << i;
    EXPECT_EQ(a[i].gyro, b[i].gyro) << i;
    EXPECT_EQ(a[i].accel, b[i].accel) << i;
  }
}

TEST(BagImu, EveryFormatGivesTheCsvRowsExactly) {
  const std::vector<ImuSample> expected = ExpectedImu();
  for (const std::vector<std::string>& files :
       std::vector<std::vector<std::string>>{{"ros1_none.bag"},
                                             {"ros1_bz2.bag"},
                                             {"ros1_lz4.bag"},
                                             {"ros1_unindexed.bag"},
                                             {"ros1_split_0.bag", "ros1_split_1.bag"},
                                             {"mcap_zstd.mcap"},
                                             {"mcap_lz4.mcap"},
                                             {"rosbag2_db3"}}) {
    SCOPED_TRACE(files[0]);
    ExpectSameSamples(ReadBagImu(Source(files)), expected);
  }
}

TEST(BagImu, ReceiveTimeIsTheRecordingTime) {
  ExpectSameSamples(ReadBagImu(Source({"ros1_lz4.bag"}, BagTime::kReceive)), ExpectedImu(),
                    kImuReceiveDelayNs);
}

TEST(BagImu, UnitsScaleTheReadingsAsTheCsvReaderDoes) {
  ImuReadOptions options;
  options.gyro_scale = M_PI / 180.0;
  const std::vector<ImuSample> scaled = ReadBagImu(Source({"mcap_none.mcap"}), options);
  const std::vector<ImuSample> expected = ExpectedImu();
  ASSERT_EQ(scaled.size(), expected.size());
  for (size_t i = 0; i < scaled.size(); ++i) {
    EXPECT_EQ(scaled[i].gyro, (M_PI / 180.0) * expected[i].gyro);
    EXPECT_EQ(scaled[i].accel, expected[i].accel);
  }
  // EuRoC's accelerometer in m/s^2 read as if in g: about 9.81 g, still not "about 1" — but the
  // reverse, m/s^2 readings divided by 9.81, look like units of g and are refused.
  ImuReadOptions in_g;
  in_g.accel_scale = 1.0 / 9.81;
  EXPECT_THAT([&] { ReadBagImu(Source({"mcap_none.mcap"}), in_g); },
              ::testing::ThrowsMessage<Error>(HasSubstr("units of g")));
}

TEST(BagImu, MissingOrWrongTopicIsNamedWithTheRecordingsImuTopics) {
  BagImuSource source = Source({"ros1_none.bag"});
  source.topic = "/imu";
  EXPECT_THAT([&] { ReadBagImu(source); },
              ::testing::ThrowsMessage<Error>(HasSubstr(
                  "--imu-topic /imu: not in " + Bag("ros1_none.bag") +
                  " (its sensor_msgs/Imu topics: /imu0)")));
  source.topic = "/other";
  EXPECT_THAT([&] { ReadBagImu(source); },
              ::testing::ThrowsMessage<Error>(
                  HasSubstr("--imu-topic /other: a std_msgs/String topic, not sensor_msgs/Imu")));
}

TEST(BagImu, StaticRecordingEqualsTheCsvReadersOfTheSameSamples) {
  testing::TempDir dir;
  const std::string csv = dir.File("imu.csv");
  {
    std::ofstream out(csv);
    WriteEurocImu(ExpectedImu(), &out);
  }
  const StaticRecording from_csv = ReadEurocStaticRecording(csv);
  const StaticRecording from_bag = ReadBagStaticRecording(Source({"ros1_bz2.bag"}));
  EXPECT_EQ(from_bag.rate_hz, from_csv.rate_hz);
  ASSERT_EQ(from_bag.axes.size(), from_csv.axes.size());
  for (size_t a = 0; a < from_bag.axes.size(); ++a) {
    EXPECT_EQ(from_bag.axes[a].sensor, from_csv.axes[a].sensor);
    EXPECT_EQ(from_bag.axes[a].axis, from_csv.axes[a].axis);
    EXPECT_EQ(from_bag.axes[a].samples, from_csv.axes[a].samples);
  }
  EXPECT_EQ(from_bag.source, Bag("ros1_bz2.bag") + ":/imu0");
}

}  // namespace
}  // namespace splinecal
