// Analytic test trajectories T_w_s(t) for the simulator (`splinecal simulate --trajectory`).
//
// Every trajectory here is built from six smooth scalar channels of time t [s]:
//
//     channel(t) = offset + rate * t + sum_k A_k sin(omega_k t + phase_k)
//
// three for the position p_w_s(t) = (x, y, z) [m] and three for roll, pitch, yaw [rad], with
//
//     R_w_s(t) = Rz(yaw) Ry(pitch) Rx(roll)
//
// so position, velocity, acceleration and the body angular rate are all exact closed forms
// (AnalyticTrajectory::Evaluate). Differentiating R = Rz Ry Rx (Rz^T dRz/dt = yaw' [e_z]x, etc.):
//
//     w_s = vee(R^T dR/dt) = Rx^T Ry^T e_z yaw' + Rx^T e_y pitch' + e_x roll'
//
// The simulator does not use these derivatives: it fits spline control poses to dense pose
// samples (estimation/pose_fit.h) and predicts the IMU from the spline, so that the IMU file is
// exactly the spline's prediction. The closed forms check that fit (tests/imu/).
//
// The trajectories (times in seconds from the trajectory's own t = 0):
//   vio_course  the "VIO from scratch" course trajectory [seed000 §2]: K = pi / 10,
//               p = (15 cos(K t) + 5, 20 sin(K t) + 5, sin(10 K t) + 5),
//               (roll, pitch, yaw) = (0.1 cos t, 0.2 sin t, K t). One ellipse every 20 s.
//   figure8     a lemniscate of Gerono, 20 s per figure: W = 2 pi / 20,
//               p = (10 sin(W t), 5 sin(2 W t), 2 + 0.5 sin(3 W t)),
//               (roll, pitch, yaw) = (0.3 sin(2 W t), 0.2 sin(W t + 0.5), 1.2 sin(W t)).
//               Peak speed 4.5 m/s, acceleration <= 2.4 m/s^2, body rate <= 0.63 rad/s.
//   random      seeded sums of sinusoids with bounded body rate and linear acceleration (see
//               RandomTrajectoryOptions for the guarantees).
#ifndef SPLINECAL_SIM_TRAJECTORIES_H_
#define SPLINECAL_SIM_TRAJECTORIES_H_

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

// offset + rate * t + sum_k amplitude_k sin(omega_k t + phase_k).
struct SinusoidChannel {
  struct Term {
    double amplitude = 0.0;
    double omega_rad_s = 0.0;
    double phase_rad = 0.0;
  };
  double offset = 0.0;
  double rate = 0.0;  // per second
  std::vector<Term> terms;

  // The value and its first two time derivatives at t [s]; each output may be nullptr.
  void Evaluate(double t_s, double* value, double* first, double* second) const;
};

// The exact state of an analytic trajectory at one time.
struct TrajectoryState {
  SE3d T_w_s;
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // d p_w_s / dt [m/s]
  Eigen::Vector3d a_w = Eigen::Vector3d::Zero();  // d^2 p_w_s / dt^2 [m/s^2] (no gravity)
  Eigen::Vector3d w_s = Eigen::Vector3d::Zero();  // body angular rate [rad/s]
};

class AnalyticTrajectory {
 public:
  AnalyticTrajectory(std::string name,
                     std::array<SinusoidChannel, 3> position,
                     std::array<SinusoidChannel, 3> roll_pitch_yaw);

  const std::string& name() const { return name_; }

  // The pose T_w_s(t) and its exact derivatives (see the file comment). Any finite t.
  TrajectoryState Evaluate(double t_s) const;
  SE3d Pose(double t_s) const;

  // Poses at t_ns = start_ns + k * step_ns for k = 0.. while t_ns <= end_ns; the trajectory is
  // evaluated at its own time (t_ns - start_ns) * 1e-9 s. step_ns > 0, end_ns >= start_ns.
  std::vector<StampedPose> Sample(int64_t start_ns, int64_t end_ns, int64_t step_ns) const;

  const std::array<SinusoidChannel, 3>& position() const { return position_; }
  const std::array<SinusoidChannel, 3>& roll_pitch_yaw() const { return roll_pitch_yaw_; }

 private:
  std::string name_;
  std::array<SinusoidChannel, 3> position_;
  std::array<SinusoidChannel, 3> roll_pitch_yaw_;
};

AnalyticTrajectory VioCourseTrajectory();
AnalyticTrajectory Figure8Trajectory();

struct RandomTrajectoryOptions {
  // Guaranteed bounds over all t: |w_s(t)| <= max_angular_rate_rad_s and
  // |a_w(t)| <= max_acceleration_m_s2 (the bounds are met by construction: each Euler-angle rate
  // and each acceleration axis is scaled so that the sum of its terms' peaks stays below its
  // share, |w_s| <= |roll'| + |pitch'| + |yaw'|, |a_w| <= sqrt(3) max_axis |a|).
  double max_angular_rate_rad_s = 1.0;
  double max_acceleration_m_s2 = 2.0;
  // Sinusoid periods are drawn uniformly in [min_period_s, max_period_s].
  double min_period_s = 2.0;
  double max_period_s = 20.0;
  int terms_per_channel = 4;
  // Centre of the motion [m] (position offsets).
  Eigen::Vector3d center_w = Eigen::Vector3d(0.0, 0.0, 1.5);
};

// A smooth random trajectory from a seed: the same seed gives the same trajectory on every run
// (std::mt19937_64 with our own 53-bit uniform mapping, no std distributions). Throws
// splinecal::Error for non-positive bounds or periods or terms_per_channel < 1.
AnalyticTrajectory RandomTrajectory(uint64_t seed, const RandomTrajectoryOptions& options = {});

// "vio_course", "figure8" or "random" (seeded with `seed`; the others ignore it). Throws
// splinecal::Error naming the valid choices for anything else.
AnalyticTrajectory MakeTrajectory(const std::string& name, uint64_t seed);

}  // namespace splinecal

#endif  // SPLINECAL_SIM_TRAJECTORIES_H_
