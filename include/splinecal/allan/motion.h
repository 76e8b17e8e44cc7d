// Is a recording static? `splinecal allan` reads noise off a recording of an IMU at rest; a
// recording that moves (the EuRoC calibration sequence, waved in front of a target all the time)
// gives "noise" that is the motion, tens of thousands of times the sensor's.
//
// The test compares each axis with its own white noise. The record is cut into windows of
// window_s seconds (at least kMinWindowSamples samples); within a window the white-noise level is
// the standard deviation of first differences over sqrt(2), insensitive to slow changes, and its
// median over the windows, sigma, is the axis's white level (a few moving windows do not move a
// median). Consecutive window means of a static sensor then differ by about sqrt(2 / n) sigma for
// n samples per window: white noise averaged over a window (a sensor's own bias drift over one
// second is far smaller, and a filter only lowers it). An axis moves where
//
//     | mean_{w+1} - mean_w |  >  threshold_sigmas * sqrt(2 / n) * sigma,
//
// ten times what the white noise explains by default: a 10-sigma event that a static record of
// 10^5 windows shows with probability below 1e-17, while turning by a tenth of a degree moves
// an accelerometer axis by 0.017 m/s^2, twelve times the white level of the ADIS16448 over 1 s.
// The test is scale-invariant (ratios only), so the same recording with its noise scaled is
// judged alike. The turn of the gravity direction between the windows (all three accelerometer
// axes given) is reported with the result, as the tilt a user recognises.
#ifndef SPLINECAL_ALLAN_MOTION_H_
#define SPLINECAL_ALLAN_MOTION_H_

#include <cstdint>
#include <string>

#include "splinecal/imu/static_recording.h"

namespace splinecal {

struct MotionOptions {
  double window_s = 1.0;
  double threshold_sigmas = 10.0;
};

// Fewer samples per window would make the in-window white level too noisy to compare with.
constexpr int64_t kMinWindowSamples = 10;

struct MotionCheck {
  bool checked = false;  // false when the record has fewer than 3 windows
  bool moving = false;
  int64_t windows = 0;         // per axis
  int64_t moving_windows = 0;  // window pairs of any axis beyond the threshold
  // The largest ratio |mean difference| / (sqrt(2 / n) sigma) over all axes, its axis and where.
  double worst_ratio = 0.0;
  std::string worst_axis;
  double worst_at_s = 0.0;  // start of the later window, seconds from the recording's start
  double first_moving_at_s = 0.0;
  double max_tilt_deg = 0.0;  // largest turn of the mean accelerometer direction between windows

  // One sentence: what moves, where, by how much.
  std::string Summary(const MotionOptions& options = {}) const;
};

// Checks every axis of `recording` (its samples are read, not changed).
MotionCheck CheckMotion(const StaticRecording& recording, const MotionOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_MOTION_H_
