#include "splinecal/sim/simulate_camera.h"

#include <algorithm>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "splinecal/camera/rolling_shutter.h"
#include "splinecal/error.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

// A world point seen by one camera of the rig from the spline.
struct PointView {
  const SE3Splined* spline;
  const CameraCalibration* camera;
  double t_base_s;  // frame stamp + time offset, seconds since the spline's t0 (IMU clock)
  Eigen::Vector3d p_w;

  bool Row(double tau, double* v, double* v_dot) const {
    const double t = t_base_s + tau;
    if (!(t >= spline->start_time() && t <= spline->end_time())) return false;
    const Segment<double> segment = spline->SegmentAt(t);
    const internal::BodyState state =
        internal::EvaluateBodyState(spline->model(), spline->Knots(segment), segment);
    internal::PointProjection projection;
    if (!internal::ProjectPoint(
            camera->camera, camera->T_cam_imu, state, p_w, 1.0, false, &projection)) {
      return false;
    }
    *v = projection.uv.y();
    *v_dot = projection.uv_dot.y();
    return true;
  }
};

// Checks of the file comment at the solved exposure time; the noise-free pixel on success.
bool Observe(const PointView& view,
             const CameraSimulationOptions& options,
             bool target_point,
             const Eigen::Vector3d& p_t,
             Eigen::Vector2d* uv) {
  const CameraCalibration& cam = *view.camera;
  ExposureSolution solution;
  auto row = [&](double tau, double* v, double* v_dot) { return view.Row(tau, v, v_dot); };
  if (!SolveExposureTime(row,
                         cam.line_delay_s,
                         cam.camera.height,
                         0.5 * cam.line_delay_s * cam.camera.height,
                         &solution)) {
    return false;
  }
  if (solution.at_lower_bound || solution.at_upper_bound) return false;  // row outside image
  const SE3d T_w_c = view.spline->Pose(view.t_base_s + solution.tau_s) * cam.T_cam_imu.inverse();
  const Eigen::Vector3d p_c = T_w_c.inverse() * view.p_w;
  if (!(p_c.norm() >= options.min_depth_m) || !(p_c.norm() <= options.max_depth_m)) return false;
  if (!cam.camera.IsDistortionMonotonic(p_c)) return false;  // also: in the valid region
  if (!cam.camera.Project(p_c, uv) || !cam.camera.InImage(*uv)) return false;
  if (target_point && options.target.IsPlanar()) {
    const SE3d T_t_c = options.T_w_t.inverse() * T_w_c;
    const Eigen::Vector3d to_camera = T_t_c.translation() - p_t;
    if (!(T_t_c.translation().z() > 0.0)) return false;
    if (to_camera.normalized().z() < std::cos(options.max_view_angle_deg * kPi / 180.0)) {
      return false;
    }
  }
  return true;
}

}  // namespace

Eigen::Vector3d TargetCentre(const CalibrationTarget& target, const SE3d& T_w_t) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const auto& [id, p] : target.points) sum += p;
  if (target.points.empty()) return T_w_t.translation();
  return T_w_t * (sum / static_cast<double>(target.points.size()));
}

CameraSimulationResult SimulateCameras(const SE3Splined& spline,
                                       const Camchain& camchain,
                                       int64_t start_ns,
                                       int64_t end_ns,
                                       const CameraSimulationOptions& options) {
  if (camchain.empty()) throw Error("camera simulation: the camchain has no camera");
  if (!(options.camera_rate_hz > 0.0) || !std::isfinite(options.camera_rate_hz)) {
    throw Error("camera simulation: the camera rate must be positive [Hz]");
  }
  if (!(options.pixel_noise_px >= 0.0) || !std::isfinite(options.pixel_noise_px)) {
    throw Error("camera simulation: the pixel noise must be >= 0 [px]");
  }
  if (start_ns < spline.start_time_ns() || end_ns > spline.end_time_ns() || end_ns <= start_ns) {
    throw Error("camera simulation: [" + std::to_string(start_ns) + ", " + std::to_string(end_ns) +
                "] ns is not inside the spline's valid range");
  }
  CameraSimulationResult result;
  GaussianSampler noise(options.seed);
  // Landmarks first (their draws come before the pixel noise).
  if (options.num_landmarks > 0) {
    std::mt19937_64 engine(options.seed ^ 0x9e3779b97f4a7c15ULL);
    auto uniform = [&engine]() { return static_cast<double>(engine() >> 11) * 0x1.0p-53; };
    const CameraCalibration& cam = camchain[0];
    for (int k = 0; k < options.num_landmarks; ++k) {
      // A pixel with a bearing (the corners of a fisheye image may have none).
      Eigen::Vector3d bearing = Eigen::Vector3d::UnitZ();
      for (int attempt = 0; attempt < 100; ++attempt) {
        const Eigen::Vector2d uv(uniform() * (cam.camera.width - 1),
                                 uniform() * (cam.camera.height - 1));
        if (cam.camera.UnprojectToBearing(uv, &bearing)) break;
      }
      const double t = spline.start_time() + uniform() * (spline.end_time() - spline.start_time());
      const double depth =
          options.landmark_min_depth_m +
          uniform() * (options.landmark_max_depth_m - options.landmark_min_depth_m);
      const SE3d T_w_c = spline.Pose(t) * cam.T_cam_imu.inverse();
      result.landmarks_w[kLandmarkIdBase + k] = T_w_c * (bearing * depth);
    }
  }
  const int64_t period_ns = static_cast<int64_t>(std::llround(1e9 / options.camera_rate_hz));
  for (size_t cam_id = 0; cam_id < camchain.size(); ++cam_id) {
    const CameraCalibration& cam = camchain[cam_id];
    const int64_t shift_ns = static_cast<int64_t>(std::llround(cam.time_offset_s * 1e9));
    const int64_t readout_ns =
        static_cast<int64_t>(std::ceil(cam.line_delay_s * (cam.camera.height - 1) * 1e9));
    const int64_t first_ns = start_ns - shift_ns;  // camera clock
    for (int64_t k = 0;; ++k) {
      const int64_t t_cam_ns =
          first_ns +
          static_cast<int64_t>(std::llround(static_cast<double>(k) * 1e9 / options.camera_rate_hz));
      if (t_cam_ns + shift_ns + readout_ns + 1 > end_ns) break;
      if (k > 0 && period_ns <= 0) break;
      ++result.num_frames;
      const double t_base = spline.TimeSinceT0(t_cam_ns) + cam.time_offset_s;
      bool saw_target = false;
      auto add = [&](int64_t id, const Eigen::Vector2d& uv) {
        Observation o;
        o.t_ns = t_cam_ns;
        o.cam_id = static_cast<int>(cam_id);
        o.point_id = id;
        o.uv = uv;
        if (options.pixel_noise_px > 0.0) {
          o.uv.x() += options.pixel_noise_px * noise.Next();
          o.uv.y() += options.pixel_noise_px * noise.Next();
        }
        result.observations.push_back(o);
      };
      if (options.has_target) {
        for (const auto& [id, p_t] : options.target.points) {
          const PointView view{&spline, &cam, t_base, options.T_w_t * p_t};
          Eigen::Vector2d uv;
          if (!Observe(view, options, true, p_t, &uv)) continue;
          add(id, uv);
          saw_target = true;
          ++result.num_target_observations;
        }
      }
      for (const auto& [id, p_w] : result.landmarks_w) {
        const PointView view{&spline, &cam, t_base, p_w};
        Eigen::Vector2d uv;
        if (!Observe(view, options, false, Eigen::Vector3d::Zero(), &uv)) continue;
        add(id, uv);
        ++result.num_landmark_observations;
      }
      if (saw_target) ++result.num_frames_with_target;
    }
  }
  if (result.num_frames == 0) {
    throw Error("camera simulation: the time range is too short for one frame");
  }
  SortObservations(&result.observations);
  return result;
}

void WriteCameraSimulationTruth(const Camchain& camchain,
                                const CameraSimulationOptions& options,
                                const CameraSimulationResult& result,
                                YamlWriter* yaml) {
  yaml->BeginMap("cameras");
  for (size_t i = 0; i < camchain.size(); ++i) {
    yaml->BeginMap("cam" + std::to_string(i));
    yaml->Matrix("T_cam_imu", camchain[i].T_cam_imu.matrix());
    yaml->Scalar("timeshift_cam_imu", camchain[i].time_offset_s);  // Kalibr's key
    yaml->Scalar("line_delay", camchain[i].line_delay_s);
    yaml->EndMap();
  }
  yaml->EndMap();
  yaml->Scalar("camera_rate_hz", options.camera_rate_hz);
  yaml->Scalar("pixel_noise_px", options.pixel_noise_px);
  if (options.has_target) {
    yaml->Scalar("target_type", options.target.type);
    yaml->Matrix("T_w_t", options.T_w_t.matrix());
  }
  yaml->Scalar("num_frames", result.num_frames);
  yaml->Scalar("num_frames_with_target", result.num_frames_with_target);
  yaml->Scalar("num_target_observations", result.num_target_observations);
  yaml->Scalar("num_landmarks", static_cast<int64_t>(result.landmarks_w.size()));
  yaml->Scalar("num_landmark_observations", result.num_landmark_observations);
}

SE3d CalibrationCameraPose(double t_s, const Eigen::Vector3d& target_centre_w, uint64_t seed) {
  // Periods [s] and amplitudes of the default shape; other seeds scale the periods by
  // [0.85, 1.15] and draw the phases.
  double scale[10];
  double phase[10];
  std::mt19937_64 engine(seed);
  for (int i = 0; i < 10; ++i) {
    const double a = static_cast<double>(engine() >> 11) * 0x1.0p-53;
    const double b = static_cast<double>(engine() >> 11) * 0x1.0p-53;
    scale[i] = seed == 0 ? 1.0 : 0.85 + 0.3 * a;
    phase[i] = seed == 0 ? 0.5 * i : 2.0 * kPi * b;
  }
  auto wave = [&](int i, double amplitude, double period_s) {
    return amplitude * std::sin(2.0 * kPi * t_s / (period_s * scale[i]) + phase[i]);
  };
  const Eigen::Vector3d p =
      target_centre_w + Eigen::Vector3d(wave(0, 0.30, 5.1) + wave(1, 0.06, 1.3),
                                        wave(2, 0.22, 4.3) + wave(3, 0.05, 1.1),
                                        1.0 + wave(4, 0.15, 3.7));
  const Eigen::Vector3d look =
      target_centre_w + Eigen::Vector3d(wave(5, 0.15, 1.7), wave(6, 0.12, 2.3), 0.0);
  const Eigen::Vector3d z = (look - p).normalized();
  const Eigen::Vector3d x0 = (Eigen::Vector3d::UnitX() - z.x() * z).normalized();
  const Eigen::Vector3d y0 = z.cross(x0);
  const double psi = wave(7, 0.5, 3.1) + wave(8, 0.12, 0.9);
  const Eigen::Vector3d x = std::cos(psi) * x0 + std::sin(psi) * y0;
  Eigen::Matrix3d R;
  R.col(0) = x;
  R.col(1) = z.cross(x);
  R.col(2) = z;
  return SE3d(SO3d::FromMatrix(R), p);
}

PoseFitResult FitCalibrationTrajectory(const Eigen::Vector3d& target_centre_w,
                                       const SE3d& T_cam_imu,
                                       int64_t start_ns,
                                       int64_t end_ns,
                                       int64_t knot_spacing_ns,
                                       uint64_t seed) {
  const KnotLayout layout = KnotLayoutCovering(start_ns, end_ns, knot_spacing_ns);
  const int64_t step_ns = std::max<int64_t>(1, knot_spacing_ns / 10);
  std::vector<StampedPose> poses;
  const int64_t last_ns = layout.t0_ns + (layout.num_control_poses - 1) * layout.dt_ns;
  for (int64_t t_ns = layout.t0_ns; t_ns <= last_ns; t_ns += step_ns) {
    const SE3d T_w_s =
        CalibrationCameraPose(1e-9 * static_cast<double>(t_ns - start_ns), target_centre_w, seed) *
        T_cam_imu;
    StampedPose pose;
    pose.t_ns = t_ns;
    pose.p = T_w_s.translation();
    pose.q = T_w_s.so3().quaternion();
    poses.push_back(pose);
  }
  return FitControlPoses(poses, layout);
}

CalibrationSequence SimulateCalibrationSequence(const Camchain& camchain,
                                                const CalibrationSequenceOptions& options) {
  if (camchain.empty()) throw Error("calibration sequence: the camchain has no camera");
  if (!(options.duration_s > 0.0) || !(options.knot_spacing_s > 0.0)) {
    throw Error("calibration sequence: duration and knot spacing must be positive");
  }
  const int64_t end_ns = options.start_ns + std::llround(options.duration_s * 1e9);
  const Eigen::Vector3d centre = options.camera.has_target
                                     ? TargetCentre(options.camera.target, options.camera.T_w_t)
                                     : Eigen::Vector3d::Zero();
  const PoseFitResult fit = FitCalibrationTrajectory(centre,
                                                     camchain[0].T_cam_imu,
                                                     options.start_ns,
                                                     end_ns,
                                                     std::llround(options.knot_spacing_s * 1e9),
                                                     options.trajectory_seed);
  CalibrationSequence sequence;
  sequence.spline = fit.MakeSpline();
  SimulateImu(sequence.spline,
              options.start_ns,
              end_ns,
              options.imu,
              &sequence.imu,
              &sequence.ground_truth);
  sequence.cameras =
      SimulateCameras(sequence.spline, camchain, options.start_ns, end_ns, options.camera);
  return sequence;
}

}  // namespace splinecal
