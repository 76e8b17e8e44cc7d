// IMU samples from a bag's sensor_msgs/Imu topic (io/bag_reader.h, io/bag_messages.h), read with
// the checks of the EuRoC CSV readers (io/euroc.h, io/static_recording.h): the same scales and
// plausibility limits, times strictly increasing (a topic whose stamps go backwards or repeat is
// named with its first offending message), no gap, an accelerometer not in g, a rate an IMU has.
// Every command that reads IMU samples takes them from here with --bag FILE --imu-topic T
// (docs/bags.md, "Commands on a bag").
#ifndef SPLINECAL_IO_BAG_IMU_H_
#define SPLINECAL_IO_BAG_IMU_H_

#include <memory>
#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/euroc.h"

namespace splinecal {

// Which recording, topic and clock.
struct BagImuSource {
  std::vector<std::string> paths;  // the recording (OpenBag's paths)
  std::string topic;               // "/imu0"
  BagTime time = BagTime::kHeader;

  // "a.bag:/imu0" ("a_0.bag,a_1.bag:/imu0"): the source named in results and messages.
  std::string Name() const;
};

// The samples of one sensor_msgs/Imu topic, streamed one message at a time (memory: the bag's
// message index, never the whole bag).
class BagImuStream {
 public:
  // Opens the recording and selects the topic. Throws splinecal::Error for a bag OpenBag refuses,
  // a topic the recording does not have (naming its sensor_msgs/Imu topics, or all its topics
  // when it has none), a topic of another type, and bad scales in `options`.
  BagImuStream(const BagImuSource& source, const ImuReadOptions& options);

  // The next sample, scaled by options' gyro_scale / accel_scale; false at the end. Throws
  // splinecal::Error naming the message (file and offset) for a reading that is not finite or
  // beyond the input layer's plausibility limits (io/text_file.h), a time that does not increase,
  // and a damaged bag.
  bool Next(ImuSample* sample);

  const BagReader& bag() const { return *bag_; }
  const BagImuSource& source() const { return source_; }
  // Messages read so far.
  int64_t count() const { return count_; }

 private:
  BagImuSource source_;
  ImuReadOptions options_;
  std::unique_ptr<BagReader> bag_;
  int topic_ = -1;
  BagStamps stamps_;
  BagMessage message_;
  int64_t count_ = 0;
};

// Every sample of the topic, checked as ReadEurocImu checks imu0/data.csv: at least 2 samples,
// no gap longer than options.max_gap_periods median periods (named with the sample's index and
// time), an accelerometer not in g (unless options say so), and the rate of an IMU
// (imu/imu_rate.h).
std::vector<ImuSample> ReadBagImu(const BagImuSource& source, const ImuReadOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_IO_BAG_IMU_H_
