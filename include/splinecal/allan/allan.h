// IMU noise identification: what `splinecal allan` does, as a library call.
//
// ComputeAllan takes a static recording (one sample series per axis, imu/static_recording.h),
// computes the overlapping Allan deviation of every axis at log-spaced averaging times
// (allan/allan_deviation.h; axes in parallel on std::threads), fits the noise terms of each axis
// (allan/noise_fit.h) and combines the axes of each sensor into Kalibr's four keys
// (docs/conventions.md, "IMU model": densities, not per-sample standard deviations).
//
// The text writers give the files of `splinecal allan --out DIR`: allan.csv, result.yaml,
// imu.yaml and allan.svg (layouts in docs/allan.md).
//
// Example (in memory):
//
//   StaticRecording recording;
//   recording.rate_hz = 200.0;
//   recording.axes.push_back({ImuSensor::kGyroscope, 0, std::move(gyro_x_samples)});
//   const AllanResult result = ComputeAllan(std::move(recording));
//   const double n = result.gyroscope_noise_density.value;   // [rad/s/sqrt(Hz)]
#ifndef SPLINECAL_ALLAN_ALLAN_H_
#define SPLINECAL_ALLAN_ALLAN_H_

#include <cstdint>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include "splinecal/allan/allan_deviation.h"
#include "splinecal/allan/motion.h"
#include "splinecal/allan/noise_fit.h"
#include "splinecal/allan/work_budget.h"
#include "splinecal/imu/static_recording.h"

namespace splinecal {

enum class CombineAxes { kMean, kMax };

// What to do with a recording that moves (allan/motion.h): refuse it (throw), or compute and
// mark every term unreliable.
enum class MotionPolicy { kRefuse, kMarkUnreliable };

struct AllanOptions {
  int taus_per_decade = 10;       // averaging times per decade (before de-duplication)
  double max_tau_fraction = 0.1;  // longest averaging time, as a fraction of the record
  // Work budget: at most max_passes * N second differences per axis (allan/work_budget.h).
  // Within it every averaging time uses every start index (the overlapping estimator); beyond
  // it the short ones use every s-th. 0: no budget, always the overlapping estimator.
  int max_passes = kDefaultAllanMaxPasses;
  CombineAxes combine = CombineAxes::kMean;
  NoiseFitOptions fit;
  // The stretch analysed, in seconds from the first sample (sample index / rate): [start_s,
  // end_s). Throws when it is empty or starts beyond the recording.
  double start_s = 0.0;
  double end_s = std::numeric_limits<double>::infinity();
  MotionOptions motion;
  MotionPolicy motion_policy = MotionPolicy::kRefuse;
  // 0: the hardware's threads. Axes run in parallel; with fewer axes than threads, each axis's
  // passes are split too (results do not depend on the thread count).
  int num_threads = 0;
  // Called (from worker threads, one call at a time) as each axis finishes; may be empty.
  std::function<void(const std::string&)> progress;
};

struct AxisAllan {
  ImuSensor sensor = ImuSensor::kGyroscope;
  int axis = 0;       // 0, 1, 2: x, y, z
  std::string name;   // "gyro_x"
  double mean = 0.0;  // mean reading (the bias plus gravity, for an accelerometer)
  AllanCurve curve;
  AxisNoiseFit fit;
};

// One of Kalibr's keys, combined over the axes of its sensor.
struct KalibrKey {
  bool present = false;      // the sensor is in the input
  double value = 0.0;        // mean or max over the axes whose slope line identified it
  int num_axes = 0;          // how many axes that was
  std::string axes;          // which: "x, z"
  bool upper_bound = false;  // no axis identified it: value is the largest of the axes' bounds
  bool unreliable = false;   // the recording moves (MotionPolicy::kMarkUnreliable)
};

struct AllanResult {
  std::string source;
  double rate_hz = 0.0;
  int64_t num_samples = 0;
  int taus_per_decade = 0;
  double max_tau_fraction = 0.0;
  int max_passes = 0;
  CombineAxes combine = CombineAxes::kMean;
  double start_s = 0.0;  // the stretch analysed, seconds from the recording's first sample
  double end_s = 0.0;
  MotionCheck motion;                     // moving and allowed: every term is unreliable
  std::vector<AxisAllan> axes;            // in the recording's order
  KalibrKey gyroscope_noise_density;      // [rad/s/sqrt(Hz)]
  KalibrKey gyroscope_random_walk;        // [rad/s^2/sqrt(Hz)]
  KalibrKey accelerometer_noise_density;  // [m/s^2/sqrt(Hz)]
  KalibrKey accelerometer_random_walk;    // [m/s^3/sqrt(Hz)]
};

// The whole computation; consumes the recording's samples (memory is freed axis by axis).
// Throws splinecal::Error (naming recording.source when set) for: no axes, axes of different
// lengths, a rate that is not positive, a sample that is not finite, a constant axis, too few
// samples for 3 averaging times (the message says how many are needed), an empty --start/--end
// stretch, a negative max_passes, or motion under MotionPolicy::kRefuse.
AllanResult ComputeAllan(StaticRecording&& recording, const AllanOptions& options = {});

// The smallest number of samples that gives `count` averaging times with these options.
int64_t MinimumSamplesForAveragingTimes(int count, int taus_per_decade, double max_tau_fraction);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_ALLAN_H_
