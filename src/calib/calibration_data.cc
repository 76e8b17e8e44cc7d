#include "calibration_data.h"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <set>

#include "splinecal/error.h"
#include "splinecal/estimation/options.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace internal {

// The median frame period of one camera [s] (0.05 when it has fewer than 2 frames).
std::vector<double> FramePeriods(const std::vector<ObservationFrame>& frames, size_t num_cameras) {
  std::vector<double> periods;
  for (size_t c = 0; c < num_cameras; ++c)
    periods.push_back(FramePeriod(frames, static_cast<int>(c)));
  return periods;
}

double FramePeriod(const std::vector<ObservationFrame>& frames, int cam) {
  std::vector<int64_t> periods;
  int64_t last = 0;
  bool have = false;
  for (const ObservationFrame& f : frames) {
    if (f.cam_id != cam) continue;
    if (have) periods.push_back(f.t_ns - last);
    last = f.t_ns;
    have = true;
  }
  if (periods.empty()) return 0.05;
  std::nth_element(periods.begin(), periods.begin() + periods.size() / 2, periods.end());
  return 1e-9 * static_cast<double>(periods[periods.size() / 2]);
}

void CheckTargetSeen(const std::vector<Observation>& observations,
                     const CalibrationTarget& target) {
  for (const Observation& o : observations) {
    if (target.Find(o.point_id) != nullptr) return;
  }
  throw Error(
      "calibrate: the target is never seen: no point id in the observations is a corner "
      "of the " +
      target.type + " target (" + std::to_string(target.points.size()) +
      " corners); wrong target file, or the detector numbers corners differently");
}

void CheckInputs(const std::vector<ImuSample>& imu,
                 const std::vector<Observation>& observations,
                 const Camchain& camchain,
                 const CalibrateOptions& options) {
  if (camchain.empty()) throw Error("calibrate: the camchain has no camera");
  if (imu.size() < 2) throw Error("calibrate: fewer than 2 IMU samples");
  if (observations.empty()) throw Error("calibrate: no observations");
  if (!options.camera_chain_T_cn_c0.empty() &&
      options.camera_chain_T_cn_c0.size() != camchain.size()) {
    throw Error("calibrate: a held camera chain needs one T_cn_c0 per camera of the camchain");
  }
  if (const Observation* o = FindObservationWithoutCamera(observations, camchain)) {
    throw Error("calibrate: an observation of camera " + std::to_string(o->cam_id) + " (frame " +
                std::to_string(o->t_ns) + ") but the camchain describes " +
                std::to_string(camchain.size()) + " camera(s): wrong camchain or cam_id column");
  }
  for (size_t k = 1; k < imu.size(); ++k) {
    if (imu[k].t_ns <= imu[k - 1].t_ns) throw Error("calibrate: IMU timestamps not increasing");
  }
  auto positive = [](double v, const char* what) {
    if (!(v > 0.0) || !std::isfinite(v)) {
      throw Error(std::string("calibrate: ") + what + " must be positive");
    }
  };
  try {
    CheckSplineModelOptions(options.model);
    CheckSolverOptions(options.solver);
  } catch (const Error& e) {
    throw Error(std::string("calibrate: ") + e.what());
  }
  // Refused before anything is allocated: a spacing below two IMU periods leaves segments with
  // no IMU data and, taken to the extreme (1 ns), would ask for billions of control poses.
  const double imu_rate_hz = ImuRateHz(imu);
  if (options.model.knot_spacing_s > 0.0 &&
      options.model.knot_spacing_s < 2.0 / imu_rate_hz * (1.0 - 1e-6)) {
    throw Error("calibrate: knot spacing " + StringPrintf("%.6g", options.model.knot_spacing_s) +
                " s is below two IMU periods (" + StringPrintf("%.6g", 2.0 / imu_rate_hz) +
                " s): some segments would hold no IMU data");
  }
  positive(options.max_time_offset_s, "the time-offset range");
  if (!(options.pixel_sigma_px >= 0.0) || !(options.huber_px >= 0.0)) {
    throw Error("calibrate: the pixel sigma and the Huber threshold must be >= 0");
  }
}

// Frames whose exposure (IMU clock, camchain time offset) falls inside the IMU data.
std::vector<Observation> ObservationsInsideImu(const std::vector<ImuSample>& imu,
                                               const std::vector<Observation>& observations,
                                               const Camchain& camchain,
                                               std::vector<std::string>* warnings) {
  std::vector<Observation> inside;
  std::set<std::pair<int64_t, int>> dropped_frames;
  std::set<std::pair<int64_t, int>> frames;
  int64_t first = observations.front().t_ns;
  int64_t last = observations.front().t_ns;
  for (const Observation& o : observations) {
    const CameraCalibration& cam = camchain[o.cam_id];
    const int64_t t = o.t_ns + std::llround(cam.time_offset_s * 1e9);
    const int64_t readout = std::llround(cam.line_delay_s * (cam.camera.height - 1) * 1e9);
    frames.insert({o.t_ns, o.cam_id});
    first = std::min(first, o.t_ns);
    last = std::max(last, o.t_ns);
    if (t >= imu.front().t_ns && t + readout <= imu.back().t_ns) {
      inside.push_back(o);
    } else {
      dropped_frames.insert({o.t_ns, o.cam_id});
    }
  }
  if (inside.empty()) {
    throw Error(StringPrintf(
        "calibrate: every observation is outside the IMU's time range: frames [%.9f, "
        "%.9f] s (camera clock) vs IMU [%.9f, %.9f] s; the files are from different "
        "recordings or use different time bases (seconds vs nanoseconds, another clock "
        "origin), or timeshift_cam_imu is wrong",
        1e-9 * static_cast<double>(first),
        1e-9 * static_cast<double>(last),
        1e-9 * static_cast<double>(imu.front().t_ns),
        1e-9 * static_cast<double>(imu.back().t_ns)));
  }
  if (!dropped_frames.empty()) {
    warnings->push_back(std::to_string(dropped_frames.size()) + " of " +
                        std::to_string(frames.size()) +
                        " frames lie outside the IMU's time range and were not used");
  }
  return inside;
}

// Refuses motion that does not rotate about all three axes (file comment of calibrate.h).
void CheckRotationExcitation(const std::vector<ImuSample>& imu, double min_rate) {
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const ImuSample& s : imu) mean += s.gyro;
  mean /= static_cast<double>(imu.size());
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const ImuSample& s : imu) second += (s.gyro - mean) * (s.gyro - mean).transpose();
  second /= static_cast<double>(imu.size());
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(second);
  const Eigen::Vector3d rms = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  if (rms(0) < min_rate) {
    throw Error("calibrate: too little rotation: the gyro's RMS rate about its weakest axis is " +
                StringPrintf("%.3g", rms(0)) + " rad/s (about the others " +
                StringPrintf("%.3g", rms(1)) + " and " + StringPrintf("%.3g", rms(2)) +
                " rad/s), below " + StringPrintf("%.3g", min_rate) +
                " rad/s; T_cam_imu's rotation and the time offset cannot be determined. Record "
                "again rotating the rig about all three axes");
  }
}

// The IMU samples inside [start_ns, end_ns].
std::vector<ImuSample> ImuBetween(const std::vector<ImuSample>& imu,
                                  int64_t start_ns,
                                  int64_t end_ns) {
  std::vector<ImuSample> out;
  for (const ImuSample& s : imu) {
    if (s.t_ns >= start_ns && s.t_ns <= end_ns) out.push_back(s);
  }
  return out;
}

// The time span the calibration's spline covers [ns, IMU clock]: the frames' exposures (camchain
// time offsets and readouts) plus a margin, cut to the IMU data.
std::pair<int64_t, int64_t> SpanOfFrames(const std::vector<ImuSample>& imu,
                                         const std::vector<Observation>& observations,
                                         const Camchain& camchain) {
  int64_t first = std::numeric_limits<int64_t>::max();
  int64_t last = std::numeric_limits<int64_t>::min();
  for (const Observation& o : observations) {
    const CameraCalibration& cam = camchain[o.cam_id];
    const int64_t t = o.t_ns + std::llround(cam.time_offset_s * 1e9);
    first = std::min(first, t);
    last =
        std::max<int64_t>(last, t + std::llround(cam.line_delay_s * (cam.camera.height - 1) * 1e9));
  }
  return {std::max<int64_t>(imu.front().t_ns, first - kImuMarginNs),
          std::min<int64_t>(imu.back().t_ns, last + kImuMarginNs)};
}

// The spline layout for the camera data.
KnotLayout LayoutFor(const std::vector<ImuSample>& imu,
                     const std::vector<Observation>& observations,
                     const Camchain& camchain,
                     double knot_spacing_s) {
  const auto [start, end] = SpanOfFrames(imu, observations, camchain);
  return KnotLayoutCovering(start, end, std::llround(knot_spacing_s * 1e9));
}

// Target frames (corners of the target) of the observations.
std::vector<TargetFrame> MakeTargetFrames(const std::vector<Observation>& observations,
                                          const CalibrationTarget& target,
                                          int min_corners) {
  std::vector<TargetFrame> frames;
  std::vector<Observation> corners;
  for (const Observation& o : observations) {
    if (target.Find(o.point_id) != nullptr) corners.push_back(o);
  }
  for (const ObservationFrame& f : GroupIntoFrames(corners)) {
    if (static_cast<int>(f.observations.size()) < min_corners) continue;
    TargetFrame frame;
    frame.cam = f.cam_id;
    frame.t_ns = f.t_ns;
    for (const Observation& o : f.observations) {
      frame.ids.push_back(o.point_id);
      frame.corners.push_back({*target.Find(o.point_id), o.uv});
    }
    frames.push_back(std::move(frame));
  }
  return frames;
}

// Landmarks: the observations whose ids are not target corners, grouped by id. The reference is
// the first observation in front of its camera's image plane; rho is triangulated from the initial
// spline (the midpoint of the rays in the least-squares sense). Landmarks seen once, or with rays
// that do not intersect in front of the reference camera, are dropped.
std::vector<Landmark> MakeLandmarks(const std::vector<Observation>& observations,
                                    const CalibrationTarget* target,
                                    const Camchain& camchain,
                                    const SE3Splined& spline,
                                    std::vector<std::string>* warnings) {
  std::map<int64_t, std::vector<Observation>> by_id;
  for (const Observation& o : observations) {
    if (target != nullptr && target->Find(o.point_id) != nullptr) continue;
    by_id[o.point_id].push_back(o);
  }
  std::vector<Landmark> landmarks;
  int dropped = 0;
  for (auto& [id, obs] : by_id) {
    if (obs.size() < 2) {
      ++dropped;
      continue;
    }
    Landmark landmark;
    landmark.id = id;
    // The reference: the first observation with a ray (x, y, 1), i.e. in front of its camera's
    // image plane (inverse depth is along z; a wide-angle camera also sees points beyond 90
    // degrees). It moves to the front; the others keep their order.
    const auto reference = std::find_if(obs.begin(), obs.end(), [&](const Observation& o) {
      return camchain[o.cam_id].camera.Unproject(o.uv, &landmark.ray);
    });
    if (reference == obs.end()) {
      ++dropped;
      continue;
    }
    std::rotate(obs.begin(), reference, reference + 1);
    landmark.reference = obs.front();
    landmark.cam = obs.front().cam_id;
    // Triangulate: minimise sum |(I - d d^T)(X - c)|^2 over the rays of every observation.
    Eigen::Matrix3d A = Eigen::Matrix3d::Zero();
    Eigen::Vector3d b = Eigen::Vector3d::Zero();
    SE3d T_w_c_ref;
    bool ok = true;
    for (size_t k = 0; k < obs.size() && ok; ++k) {
      const CameraCalibration& c = camchain[obs[k].cam_id];
      const double t =
          spline.TimeSinceT0(obs[k].t_ns) + c.time_offset_s + c.line_delay_s * obs[k].uv.y();
      Eigen::Vector3d bearing;
      if (!(t >= spline.start_time() && t <= spline.end_time()) ||
          !c.camera.UnprojectToBearing(obs[k].uv, &bearing)) {
        ok = k > 0;
        break;
      }
      const SE3d T_w_c = spline.Pose(t) * c.T_cam_imu.inverse();
      if (k == 0) T_w_c_ref = T_w_c;
      const Eigen::Vector3d d = T_w_c.so3() * bearing;
      const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
      A += P;
      b += P * T_w_c.translation();
    }
    const Eigen::Vector3d p_w = A.ldlt().solve(b);
    const double depth = (T_w_c_ref.inverse() * p_w).z();
    if (!ok || !p_w.allFinite() || !(depth > 0.05)) {
      ++dropped;
      continue;
    }
    landmark.rho = 1.0 / depth;
    landmark.others.assign(obs.begin() + 1, obs.end());
    landmarks.push_back(std::move(landmark));
  }
  if (dropped > 0) {
    warnings->push_back(std::to_string(dropped) +
                        " landmark(s) seen only once or not triangulable were not used");
  }
  return landmarks;
}

}  // namespace internal
}  // namespace splinecal
