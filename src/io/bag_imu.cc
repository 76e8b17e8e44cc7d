#include "splinecal/io/bag_imu.h"

#include <algorithm>
#include <cmath>

#include "splinecal/error.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/text_file.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

// The topics of `kind` in the recording, "a, b" ("none" when there is none).
std::string TopicsOfKind(const BagReader& bag, BagMessageKind kind) {
  std::string names;
  for (const BagTopic& topic : bag.topics()) {
    if (KindOfType(topic.type) == kind) names += (names.empty() ? "" : ", ") + topic.name;
  }
  return names.empty() ? "none" : names;
}

// A reading as the CSV reader takes it (io/euroc.cc): the value as recorded within the
// plausibility limit of its unit, then scaled.
double CheckedReading(double value, double limit, double scale, const char* name,
                      const char* unit, const BagMessage& message, const std::string& topic) {
  if (!(std::abs(value) <= limit)) {
    throw Error(StringPrintf("%s: topic %s: %s is %g, not a finite number within the plausible "
                             "+-%g %s",
                             message.where.c_str(), topic.c_str(), name, value, limit, unit));
  }
  return scale * value;
}

}  // namespace

std::string BagImuSource::Name() const {
  std::string name;
  for (const std::string& path : paths) name += (name.empty() ? "" : ",") + path;
  return name + ":" + topic;
}

BagImuStream::BagImuStream(const BagImuSource& source, const ImuReadOptions& options)
    : source_(source), options_(options), stamps_(source.time, 0) {
  if (!(std::isfinite(options.gyro_scale) && options.gyro_scale > 0.0 &&
        std::isfinite(options.accel_scale) && options.accel_scale > 0.0)) {
    throw Error("IMU scales must be positive and finite");
  }
  bag_ = OpenBag(source.paths);
  topic_ = bag_->FindTopic(source.topic);
  if (topic_ < 0) {
    const std::string imu_topics = TopicsOfKind(*bag_, BagMessageKind::kImu);
    std::string all;
    for (const BagTopic& topic : bag_->topics()) all += (all.empty() ? "" : ", ") + topic.name;
    throw Error("--imu-topic " + source.topic + ": not in " + source.paths.front() +
                (imu_topics != "none" ? " (its sensor_msgs/Imu topics: " + imu_topics + ")"
                                      : " (no sensor_msgs/Imu topic; its topics: " +
                                            (all.empty() ? std::string("none") : all) + ")"));
  }
  const BagTopic& topic = bag_->topics()[topic_];
  if (KindOfType(topic.type) != BagMessageKind::kImu) {
    throw Error("--imu-topic " + source.topic + ": a " + topic.type +
                " topic, not sensor_msgs/Imu (the recording's IMU topics: " +
                TopicsOfKind(*bag_, BagMessageKind::kImu) + ")");
  }
  bag_->SelectTopics({topic_});
  stamps_ = BagStamps(source.time, bag_->topics().size());
}

bool BagImuStream::Next(ImuSample* sample) {
  if (!bag_->Next(&message_)) return false;
  const BagTopic& topic = bag_->topics()[message_.topic];
  const ImuMessage imu = ParseImuMessage(topic, message_);
  static const char* const kGyro[] = {"angular_velocity.x", "angular_velocity.y",
                                      "angular_velocity.z"};
  static const char* const kAccel[] = {"linear_acceleration.x", "linear_acceleration.y",
                                       "linear_acceleration.z"};
  for (int i = 0; i < 3; ++i) {
    sample->gyro[i] = CheckedReading(imu.gyro[i], kMaxAngularRate, options_.gyro_scale, kGyro[i],
                                     "rad/s", message_, topic.name);
    sample->accel[i] = CheckedReading(imu.accel[i], kMaxAcceleration, options_.accel_scale,
                                      kAccel[i], "m/s^2", message_, topic.name);
  }
  sample->t_ns = stamps_.Stamp(topic, message_, imu.stamp_ns);
  ++count_;
  return true;
}

std::vector<ImuSample> ReadBagImu(const BagImuSource& source, const ImuReadOptions& options) {
  BagImuStream stream(source, options);
  std::vector<ImuSample> samples;
  samples.reserve(static_cast<size_t>(stream.bag().topics()[stream.bag().FindTopic(source.topic)]
                                          .message_count));
  ImuSample sample;
  while (stream.Next(&sample)) samples.push_back(sample);
  const std::string name = source.Name();
  if (samples.size() < 2) {
    throw Error(name + ": needs at least 2 IMU samples, found " + std::to_string(samples.size()));
  }
  // The gap check of the CSV reader (io/row_checks.cc, TimestampChecker::CheckGaps): against the
  // median period, naming the sample after the gap.
  std::vector<int64_t> times(samples.size());
  for (size_t i = 0; i < samples.size(); ++i) times[i] = samples[i].t_ns;
  const double median = static_cast<double>(MedianPeriodNs(times));
  if (samples.size() >= 3) {
    for (size_t i = 1; i < samples.size(); ++i) {
      const int64_t period = times[i] - times[i - 1];
      if (period > options.max_gap_periods * median) {
        throw Error(StringPrintf("%s: gap of %.6g s before message %zu (t = %lld ns; %.4g times "
                                 "the median period of %.6g s)",
                                 name.c_str(), period * 1e-9, i + 1,
                                 static_cast<long long>(times[i]), period / median,
                                 median * 1e-9));
      }
    }
  }
  if (options.check_accel_units) CheckAccelNotInG(samples, name);
  CheckImuRate(ImuRateHz(samples), name);
  return samples;
}

}  // namespace splinecal
