#include "splinecal/sim/simulate_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <vector>

#include "calib/camera_test_scene.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/error.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace {

constexpr int64_t kStartNs = 1'000'000'000;
constexpr int64_t kEndNs = 9'000'000'000;       // 8 s
constexpr int64_t kKnotSpacingNs = 50'000'000;  // 0.05 s

Camchain RollingShutterRig() {
  CameraCalibration c;
  c.camera = testing::EurocCamera();
  c.T_cam_imu =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.02, -0.01, 1.55)), Eigen::Vector3d(0.06, -0.02, 0.01));
  c.time_offset_s = 0.0042;
  c.line_delay_s = 3e-5;
  return {c};
}

class SimulateCamerasTest : public ::testing::Test {
 protected:
  SimulateCamerasTest()
      : rig_(RollingShutterRig()),
        fit_(FitCalibrationTrajectory(
            TargetCentre(Target(), SE3d()), rig_[0].T_cam_imu, kStartNs, kEndNs, kKnotSpacingNs)),
        spline_(fit_.MakeSpline()) {
    options_.has_target = true;
    options_.target = Target();
    options_.pixel_noise_px = 0.0;
  }
  static CalibrationTarget Target() { return MakeAprilGrid(6, 6, 0.088, 0.3); }

  Camchain rig_;
  PoseFitResult fit_;
  SE3Splined spline_;
  CameraSimulationOptions options_;
};

TEST_F(SimulateCamerasTest, TrajectoryFitsAndKeepsTheTargetInView) {
  EXPECT_LT(fit_.position_rms_m, 1e-4);
  EXPECT_LT(fit_.rotation_rms_deg, 0.01);
  const CameraSimulationResult r = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  EXPECT_GE(r.num_frames, 155);  // 20 Hz over 8 s less the readout at the end
  EXPECT_GE(r.num_frames_with_target, 0.95 * r.num_frames);
  EXPECT_GE(r.num_target_observations, 50 * r.num_frames);
  // Lively: body rates above 1 rad/s and accelerations above 1 m/s^2 somewhere.
  double max_rate = 0.0, max_accel = 0.0;
  for (double t = spline_.start_time(); t < spline_.end_time(); t += 0.01) {
    SE3d T;
    Eigen::Vector3d w, a;
    spline_.Evaluate(spline_.SegmentAt(t), &T, &w, nullptr, nullptr, &a);
    max_rate = std::max(max_rate, w.norm());
    max_accel = std::max(max_accel, a.norm());
  }
  EXPECT_GT(max_rate, 1.0);
  EXPECT_GT(max_accel, 1.0);
}

TEST_F(SimulateCamerasTest, NoiseFreeObservationsAreTheReprojectionModel) {
  // Every simulated pixel is reproduced by the calibration's residual (independent code paths
  // for time: the simulator solves on the spline, the cost on the parameter blocks).
  const CameraSimulationResult r = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  const std::vector<ObservationFrame> frames = GroupIntoFrames(r.observations);
  ReprojectionOptions settings;
  settings.camera = &rig_[0].camera;
  settings.layout = spline_.layout();
  std::vector<std::array<double, 7>> blocks(spline_.num_control_poses());
  for (int i = 0; i < spline_.num_control_poses(); ++i) {
    PoseToBlock(spline_.control_pose(i), blocks[i].data());
  }
  std::array<double, 7> T_c_s;
  PoseToBlock(rig_[0].T_cam_imu, T_c_s.data());
  double shift = rig_[0].time_offset_s;
  double line_delay = rig_[0].line_delay_s;
  std::array<double, 7> T_w_t;
  PoseToBlock(SE3d(), T_w_t.data());
  double max_error = 0.0;
  for (size_t f = 0; f < frames.size(); f += 7) {
    const double t_frame = spline_.TimeSinceT0(frames[f].t_ns);
    ControlPoseWindow window;
    ASSERT_TRUE(settings.layout.WindowCovering(
        t_frame + shift, t_frame + shift + line_delay * 480, &window));
    std::vector<TargetCornerObservation> corners;
    for (const Observation& o : frames[f].observations) {
      corners.push_back({*options_.target.Find(o.point_id), o.uv});
    }
    const TargetFrameCostFunction cost(settings, window, t_frame, corners);
    std::vector<double*> parameters;
    for (int i = 0; i < window.num_poses; ++i)
      parameters.push_back(blocks[window.first_index + i].data());
    parameters.push_back(T_c_s.data());
    parameters.push_back(&shift);
    parameters.push_back(&line_delay);
    parameters.push_back(T_w_t.data());
    std::vector<double> residuals(cost.num_residuals());
    ASSERT_TRUE(cost.Evaluate(parameters.data(), residuals.data(), nullptr));
    for (double x : residuals) max_error = std::max(max_error, std::abs(x));
  }
  EXPECT_LT(max_error, 1e-8);
}

TEST_F(SimulateCamerasTest, PixelNoiseHasTheRequestedStdAndIsSeeded) {
  options_.pixel_noise_px = 0.5;
  const CameraSimulationResult noisy = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  const CameraSimulationResult again = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  options_.pixel_noise_px = 0.0;
  const CameraSimulationResult clean = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  ASSERT_EQ(noisy.observations.size(), clean.observations.size());
  ASSERT_EQ(noisy.observations.size(), again.observations.size());
  double sum_sq = 0.0;
  for (size_t i = 0; i < noisy.observations.size(); ++i) {
    EXPECT_EQ(noisy.observations[i].uv, again.observations[i].uv);
    sum_sq += (noisy.observations[i].uv - clean.observations[i].uv).squaredNorm();
  }
  const double std_px = std::sqrt(sum_sq / (2.0 * noisy.observations.size()));
  EXPECT_NEAR(std_px, 0.5, 0.01);  // ~20000 draws: relative std error ~0.5%
}

TEST_F(SimulateCamerasTest, RollingShutterMovesPixelsAndGlobalShutterDoesNot) {
  const CameraSimulationResult rolling = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  Camchain global = rig_;
  global[0].line_delay_s = 0.0;
  const CameraSimulationResult still = SimulateCameras(spline_, global, kStartNs, kEndNs, options_);
  std::map<std::pair<int64_t, int64_t>, Eigen::Vector2d> gs;
  for (const Observation& o : still.observations) gs[{o.t_ns, o.point_id}] = o.uv;
  double max_shift = 0.0;
  for (const Observation& o : rolling.observations) {
    const auto it = gs.find({o.t_ns, o.point_id});
    if (it != gs.end()) max_shift = std::max(max_shift, (it->second - o.uv).norm());
  }
  // 14 ms of readout at image speeds of several hundred px/s: pixels move by several px.
  EXPECT_GT(max_shift, 3.0);
}

TEST_F(SimulateCamerasTest, LandmarksAreSeenRepeatedly) {
  options_.has_target = false;
  options_.num_landmarks = 300;
  const CameraSimulationResult r = SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_);
  EXPECT_EQ(r.landmarks_w.size(), 300u);
  EXPECT_EQ(r.num_target_observations, 0);
  std::map<int64_t, int> count;
  for (const Observation& o : r.observations) {
    EXPECT_GE(o.point_id, kLandmarkIdBase);
    ++count[o.point_id];
  }
  int seen_twice = 0;
  for (const auto& [id, n] : count) seen_twice += n >= 2;
  EXPECT_GE(seen_twice, 250);
}

TEST_F(SimulateCamerasTest, RefusesBadOptions) {
  options_.camera_rate_hz = 0.0;
  EXPECT_THROW(SimulateCameras(spline_, rig_, kStartNs, kEndNs, options_), Error);
  options_.camera_rate_hz = 20.0;
  EXPECT_THROW(SimulateCameras(spline_, rig_, kStartNs - 10'000'000'000, kEndNs, options_), Error);
  EXPECT_THROW(SimulateCameras(spline_, Camchain(), kStartNs, kEndNs, options_), Error);
}

}  // namespace
}  // namespace splinecal
