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
//             orientation is a true rotation through Exp). w(s), a(s) are linear between the
//             samples (stage readings at s = h/2 are the averages). With the stage slopes
//               k1 = (w_k,                    R_k a_k + g,               v)
//               k2 = (Jr^-1(th2) w_m,         R_k Exp(th2) a_m + g,      v + h/2 kv1),  th2 = h/2
//               kth1 k3 = (Jr^-1(th3) w_m,         R_k Exp(th3) a_m + g,      v + h/2 kv2),  th3 =
//               h/2 kth2 k4 = (Jr^-1(th4) w_{k+1},     R_k Exp(th4) a_{k+1} + g,  v + h kv3), th4 =
//               h kth3
//             the state advances by h/6 (k1 + 2 k2 + 2 k3 + k4) and R_{k+1} = R_k Exp(theta).
//
// Orders (global error on a smooth trajectory, h -> 0): Euler 1, midpoint 2. RK4 integrates
// the linearly interpolated readings with O(h^4) error, but that interpolation itself differs
// from the true motion by O(h^2), so on sampled IMU data RK4 is also order 2 — with a smaller
// constant than midpoint (its position update is exact for linear acceleration, and its
// rotation keeps the h^3 commutator term that the midpoint rate average drops). Measured in
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
#include "splinecal/io/euroc.h"
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
