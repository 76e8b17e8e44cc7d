// IMU dead reckoning (strapdown integration) with Euler, midpoint and RK4 steps, and the drift
// of an integrated trajectory against ground truth (`splinecal integrate`).
//
// State: position p_w_s, orientation R_w_s, world velocity v_w; IMU model and frames as in
// docs/conventions.md ("IMU model"): with bias-corrected readings w = gyro - b_g,
// a = accel - b_a and gravity g_w = (0, 0, -g),
//
//     dR_w_s/dt = R_w_s [w]x,     dv_w/dt = R_w_s a + g_w,     dp_w_s/dt = v_w.
//
// The biases are constant during the integration (the ground truth's at the start). One step
// from sample k (time t_k, readings w_k, a_k) to k+1, h = t_{k+1} - t_k [s]; Exp is the exact
// SO(3) exponential (lie/so3.h). The Euler and midpoint steps are those of [seed000 §2]:
//
//   euler     a_w = R_k a_k + g_w
//             p += v h + a_w h^2 / 2,   v += a_w h,   R_{k+1} = R_k Exp(w_k h)
//   midpoint  R_{k+1} = R_k Exp((w_k + w_{k+1}) / 2 h)
//             a_w = (R_k a_k + R_{k+1} a_{k+1}) / 2 + g_w
//             p += v h + a_w h^2 / 2,   v += a_w h
//   rk4       the classical 4-stage Runge-Kutta method on (theta, v, p), where
//             R(t_k + s) = R_k Exp(theta(s)) and theta' = Jr^-1(theta) w(s) (the Runge-Kutta-
//             Munthe-Kaas form [Iserles00]: RK4 in the local coordinate theta, so every
//             orientation is a true rotation through Exp). Stage readings at s = h/2: the
//             accelerometer linearly interpolated, a_m = (a_k + a_{k+1}) / 2; the gyro from the
//             cubic through the four samples k-1..k+2 (w_m = (-w_{k-1} + 9 w_k + 9 w_{k+1}
//             - w_{k+2}) / 16 for uniform samples; quadratic or linear at the ends of the data).
//             With the stage slopes
//               k1 = (w_k,                    R_k a_k + g,               v)
//               k2 = (Jr^-1(th2) w_m,         R_k Exp(th2) a_m + g,      v + h/2 kv1),  th2 = h/2
//               kth1 k3 = (Jr^-1(th3) w_m,         R_k Exp(th3) a_m + g,      v + h/2 kv2),  th3 =
//               h/2 kth2 k4 = (Jr^-1(th4) w_{k+1},     R_k Exp(th4) a_{k+1} + g,  v + h kv3), th4 =
//               h kth3
//             the state advances by h/6 (k1 + 2 k2 + 2 k3 + k4) and R_{k+1} = R_k Exp(theta).
//
// Why the gyro's mid-step reading is cubic. An orientation error d_theta misprojects gravity
// and grows into a position error ~ g d_theta T^2 / 2, so position accuracy is bounded by
// rotation accuracy. Integrating a linearly interpolated rate has a global rotation error
// O(h^2) whatever the integrator; with the cubic, RK4's rotation is O(h^4). Measured on the
// simulator's vio_course (noise-free, 20 s at 200 Hz): with both readings linear, RK4 ended
// 5.1e-4 m off against midpoint's 3.3e-4 m; with the cubic gyro 1.4e-4 m (rotation 5e-10 deg
// against 1.3e-4 deg). The accelerometer stays linear: the simulator's spline (cubic B-spline,
// C^2 position) has a specific force with kinks at its knots, where a cubic through four samples
// is worse than the line (measured 1.2e-3 m with a cubic accelerometer).
//
// Orders (global position error on a smooth trajectory, h -> 0): Euler 1, midpoint 2, RK4 2
// (limited by the linear accelerometer interpolation; its rotation is order 4). Measured in
// tests/imu/integrate_test.cc and docs/integrate.md.
//
// References: [seed000 §2] Euler vs midpoint integration; [Iserles00] A. Iserles,
// H. Munthe-Kaas, S. Norsett, A. Zanna, "Lie-group methods", Acta Numerica 9, 2000
// (Runge-Kutta-Munthe-Kaas); [Sola18] Jr^-1.
#ifndef SPLINECAL_IMU_INTEGRATE_H_
#define SPLINECAL_IMU_INTEGRATE_H_

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/ground_truth.h"
#include "splinecal/lie/so3.h"

namespace splinecal {

enum class IntegrationMethod { kEuler, kMidpoint, kRk4 };

// "euler", "midpoint", "rk4".
const char* IntegrationMethodName(IntegrationMethod method);
// Parses one name (as above), or a comma-separated list of them. Throws splinecal::Error naming
// the valid choices.
IntegrationMethod ParseIntegrationMethod(const std::string& name);
std::vector<IntegrationMethod> ParseIntegrationMethods(const std::string& comma_list);

// A navigation state at one time.
struct NavState {
  int64_t t_ns = 0;
  Eigen::Vector3d p_w_s = Eigen::Vector3d::Zero();  // [m]
  SO3d R_w_s;
  Eigen::Vector3d v_w = Eigen::Vector3d::Zero();  // [m/s]
};

struct ImuBias {
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();   // b_g [rad/s]
  Eigen::Vector3d accel = Eigen::Vector3d::Zero();  // b_a [m/s^2]
};

// The ground-truth row as a start state (pose and velocity) and its biases.
NavState NavStateFromGroundTruth(const GroundTruthState& state);
ImuBias BiasFromGroundTruth(const GroundTruthState& state);
// An integrated state as a EuRoC ground-truth row (with the biases used), for
// trajectory_<method>.csv.
GroundTruthState ToGroundTruthState(const NavState& state, const ImuBias& bias);

// Dead reckoning from `start` (at start.t_ns) to end_ns through `imu` (strictly increasing
// t_ns). A start or end between two samples uses readings interpolated linearly there; the steps
// in between go sample to sample. Returns the state at end_ns. If `trajectory` is not nullptr it
// receives every state: start, each IMU time in (start.t_ns, end_ns), and end_ns.
// g_w: gravity in the world frame, (0, 0, -9.81) by convention.
// Throws splinecal::Error if imu has fewer than 2 samples, start.t_ns is outside
// [imu.front().t_ns, imu.back().t_ns], or end_ns outside [start.t_ns, imu.back().t_ns].
NavState IntegrateImu(const std::vector<ImuSample>& imu,
                      const NavState& start,
                      int64_t end_ns,
                      const ImuBias& bias,
                      const Eigen::Vector3d& g_w,
                      IntegrationMethod method,
                      std::vector<NavState>* trajectory = nullptr);

// The state at t_ns, interpolated between the two neighbouring states of `trajectory` (strictly
// increasing t_ns): position by the cubic Hermite polynomial through both positions and
// velocities (error O(h^4)), velocity linearly, orientation R_a Exp(s Log(R_a^-1 R_b)),
// s = (t - t_a) / (t_b - t_a). Throws splinecal::Error if t_ns is outside the trajectory.
NavState InterpolateNavState(const std::vector<NavState>& trajectory, int64_t t_ns);

// Drift of an integrated trajectory against ground truth, compared at every ground-truth time
// inside [trajectory.front().t_ns, trajectory.back().t_ns] (the trajectory interpolated there).
// No alignment: the integration starts from the ground-truth state, so both share one frame.
struct DriftMetrics {
  double final_position_error_m = 0.0;    // |p - p_gt| at the last compared time
  double final_rotation_error_deg = 0.0;  // angle of R_gt^T R at the last compared time
  double ate_rmse_m = 0.0;                // sqrt(mean |p - p_gt|^2) over the compared times
  int64_t num_compared = 0;
  int64_t final_t_ns = 0;
};
// Throws splinecal::Error if no ground-truth time falls inside the trajectory.
DriftMetrics ComputeDrift(const std::vector<NavState>& trajectory,
                          const std::vector<GroundTruthState>& ground_truth);

namespace internal {

// Step-sized SO(3) helpers of the integrator (exposed for tests). For the rotation vector of one
// IMU step, |phi| < 0.1 rad (every step below 20 rad/s at 200 Hz), they use the Taylor series
// kept to t^8, t = |phi| (first dropped term below 3e-20 relative: exact to double rounding)
// instead of sin/cos/sqrt; above 0.1 rad the closed forms of lie/so3.h.
//   StepExp(phi)              = SO3d::Exp(phi)
//   RotateByExp(phi, x)       = Exp(phi) x = x + sin t / t  phi x x + (1 - cos t) / t^2  phi x (phi
//   x x) RightJacobianInverseTimes = Jr^-1(phi) w = w + 1/2 phi x w + c phi x (phi x w),
//                               c = 1/t^2 - cot(t/2) / (2 t)   (lie/so3.h)
SO3d StepExp(const Eigen::Vector3d& phi);
Eigen::Vector3d RotateByExp(const Eigen::Vector3d& phi, const Eigen::Vector3d& x);
Eigen::Vector3d RightJacobianInverseTimes(const Eigen::Vector3d& phi, const Eigen::Vector3d& w);

}  // namespace internal

}  // namespace splinecal

#endif  // SPLINECAL_IMU_INTEGRATE_H_
