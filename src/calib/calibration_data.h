// What `splinecal calibrate` makes of its inputs before the problem is built (private to
// src/calib/): input checks, the spline's time span, target frames and natural landmarks.
#ifndef SPLINECAL_SRC_CALIB_CALIBRATION_DATA_H_
#define SPLINECAL_SRC_CALIB_CALIBRATION_DATA_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/target.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {
namespace internal {

// The initial spline extends this far beyond the camera's time span into the IMU data [ns].
constexpr int64_t kImuMarginNs = 200'000'000;

struct TargetFrame {
  int cam = 0;
  int64_t t_ns = 0;
  std::vector<int64_t> ids;
  std::vector<TargetCornerObservation> corners;
};

struct Landmark {
  int64_t id = 0;
  int cam = 0;  // the reference observation's camera
  Observation reference;
  Eigen::Vector3d ray = Eigen::Vector3d::UnitZ();
  double rho = 0.0;
  std::vector<Observation> others;
};

// The median frame period of one camera [s] (0.05 when it has fewer than 2 frames).
double FramePeriod(const std::vector<ObservationFrame>& frames, int cam);
// FramePeriod of cameras 0 .. num_cameras - 1.
std::vector<double> FramePeriods(const std::vector<ObservationFrame>& frames, size_t num_cameras);

// Throws splinecal::Error when no observation has a point id of `target`.
void CheckTargetSeen(const std::vector<Observation>& observations, const CalibrationTarget& target);

void CheckInputs(const std::vector<ImuSample>& imu,
                 const std::vector<Observation>& observations,
                 const Camchain& camchain,
                 const CalibrateOptions& options);

// Frames whose exposure (IMU clock, camchain time offset) falls inside the IMU data.
std::vector<Observation> ObservationsInsideImu(const std::vector<ImuSample>& imu,
                                               const std::vector<Observation>& observations,
                                               const Camchain& camchain,
                                               std::vector<std::string>* warnings);

// Refuses motion that does not rotate about all three axes (file comment of calibrate.h).
void CheckRotationExcitation(const std::vector<ImuSample>& imu, double min_rate);

// The IMU samples inside [start_ns, end_ns].
std::vector<ImuSample> ImuBetween(const std::vector<ImuSample>& imu,
                                  int64_t start_ns,
                                  int64_t end_ns);

// The time span the calibration's spline covers [ns, IMU clock]: the frames' exposures (camchain
// time offsets and readouts) plus a margin, cut to the IMU data.
std::pair<int64_t, int64_t> SpanOfFrames(const std::vector<ImuSample>& imu,
                                         const std::vector<Observation>& observations,
                                         const Camchain& camchain);

// The spline layout for the camera data.
KnotLayout LayoutFor(const std::vector<ImuSample>& imu,
                     const std::vector<Observation>& observations,
                     const Camchain& camchain,
                     double knot_spacing_s);

// Target frames (corners of the target) of the observations.
std::vector<TargetFrame> MakeTargetFrames(const std::vector<Observation>& observations,
                                          const CalibrationTarget& target,
                                          int min_corners);

// Landmarks: the observations whose ids are not target corners, grouped by id. The reference is
// the first observation; rho is triangulated from the initial spline (the midpoint of the rays
// in the least-squares sense). Landmarks seen once, or with rays that do not intersect in front
// of the reference camera, are dropped.
std::vector<Landmark> MakeLandmarks(const std::vector<Observation>& observations,
                                    const CalibrationTarget* target,
                                    const Camchain& camchain,
                                    const SE3Splined& spline,
                                    std::vector<std::string>* warnings);

}  // namespace internal
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CALIB_CALIBRATION_DATA_H_
