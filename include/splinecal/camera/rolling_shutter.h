// Rolling shutter: when is a point exposed? ([Lovegrove13 §5], docs/conventions.md "Camera, time
// offset, rolling shutter").
//
// Image row r of a frame stamped t_frame (camera clock) is exposed at t_frame + r * line_delay.
// In the IMU clock (t_imu = t_cam + time_offset) a point seen in that frame is exposed at
//
//     t = t_frame + time_offset + tau,      tau = line_delay * v(t)
//
// where v(t) is the image row the point projects to at time t: the exposure time depends on the
// row, which depends on the exposure time. We solve the scalar equation
//
//     F(tau) = tau - line_delay * v(tau) = 0,     F'(tau) = 1 - line_delay * dv/dt
//
// by Newton's method with the ANALYTIC time derivative dv/dt of the projection (the camera's
// motion from the spline's body twist, estimation/reprojection_cost.h), tau clamped to the frame's
// readout [0, (height - 1) line_delay], stopping when a step is below the tolerance (the
// solution is then the point where the step was computed: its row and rate are already known,
// and it is within the tolerance of the root). F' is 1 minus the ratio of the point's image speed
// to the shutter's sweep speed (1 / line_delay rows/s): for any real motion far from 0, so Newton
// converges quadratically; from tau_0 = line_delay * (observed row) two or three iterations
// reach 1e-12 s. (The seed's first-order correction, [seed002], is one step of this iteration.)
//
// Implicit-function Jacobians. With G(theta, tau) the pixel at fixed tau, g_dot = dG/dtau (the
// pixel's velocity) and D = F'(tau*) = 1 - line_delay g_dot_v at the solution, for any parameter
// theta other than the line delay (control poses, extrinsic, time shift, the point):
//
//     d tau / d theta = line_delay dG_v/dtheta / D
//     d uv / d theta  = M dG/dtheta,         M = I + (line_delay / D) g_dot e_v^T   (2x2)
//     d uv / d line_delay = g_dot v / D      (v = the solved row, tau = line_delay v)
//
// When tau sits on a clamp bound the bound is the solution: d tau / d theta = 0 (M = I) and
// d tau / d line_delay = 0 at the lower bound, (height - 1) at the upper one. With
// line_delay = 0 the solution is tau = 0 exactly, M = I: a global shutter, bit for bit.
#ifndef SPLINECAL_CAMERA_ROLLING_SHUTTER_H_
#define SPLINECAL_CAMERA_ROLLING_SHUTTER_H_

#include <Eigen/Core>
#include <algorithm>
#include <cmath>

namespace splinecal {

struct ExposureSolveOptions {
  // Stop when a Newton step moves tau by less than this [s] (1e-12 s: a pixel moving at
  // 1e4 px/s moves 1e-8 px in that time).
  double tolerance_s = 1e-12;
  int max_iterations = 10;
};

struct ExposureSolution {
  double tau_s = 0.0;       // exposure time after t_frame + time_offset [s]
  double row = 0.0;         // v at tau (the predicted row) [px]
  double row_rate = 0.0;    // dv/dt at tau [px/s]
  double derivative = 1.0;  // D = 1 - line_delay * row_rate
  int iterations = 0;
  bool at_lower_bound = false;  // tau = 0
  bool at_upper_bound = false;  // tau = (height - 1) * line_delay
};

// Solves tau = line_delay * v(tau) on [0, (height - 1) line_delay]. row_at(tau, &v, &dv_dt)
// evaluates the predicted row and its time derivative at tau and returns false when the point
// does not project (the solve then fails). tau0 is the starting point (clamped), e.g.
// line_delay * observed row. Returns false when row_at fails, D <= 0 (the point crosses rows
// faster than the shutter sweeps: no unique exposure time), or Newton does not converge.
template <typename RowFunction>
bool SolveExposureTime(const RowFunction& row_at,
                       double line_delay_s,
                       int height,
                       double tau0_s,
                       ExposureSolution* solution,
                       const ExposureSolveOptions& options = ExposureSolveOptions()) {
  ExposureSolution s;
  const double tau_max = line_delay_s * (height - 1);
  if (!(line_delay_s > 0.0)) {  // global shutter: exact, no iteration
    s.tau_s = 0.0;
    if (!row_at(0.0, &s.row, &s.row_rate)) return false;
    s.derivative = 1.0;
    // The readout [0, 0] clamps a row outside the image as soon as the line delay grows: the
    // one-sided derivative with respect to the line delay is that of the clamped solution.
    s.at_lower_bound = s.row < 0.0;
    s.at_upper_bound = s.row > height - 1;
    *solution = s;
    return true;
  }
  double tau = std::clamp(tau0_s, 0.0, tau_max);
  for (s.iterations = 1; s.iterations <= options.max_iterations; ++s.iterations) {
    double v = 0.0;
    double v_dot = 0.0;
    if (!row_at(tau, &v, &v_dot)) return false;
    const double D = 1.0 - line_delay_s * v_dot;
    if (!(D > 0.0)) return false;
    const double F = tau - line_delay_s * v;
    const double next = std::clamp(tau - F / D, 0.0, tau_max);
    if (std::abs(next - tau) < options.tolerance_s) {
      // Converged: tau is within the step (< tolerance) of the root, and row, rate and D were
      // evaluated at tau itself (no extra evaluation at `next`).
      s.tau_s = tau;
      s.row = v;
      s.row_rate = v_dot;
      s.derivative = D;
      s.at_lower_bound = tau == 0.0 && F > 0.0;
      s.at_upper_bound = tau == tau_max && F < 0.0;
      *solution = s;
      return true;
    }
    tau = next;
  }
  return false;
}

// The 2x2 factor M of the implicit-function Jacobians (file comment): d uv / d theta =
// M dG / d theta for every parameter except the line delay. Identity on a clamp bound.
inline Eigen::Matrix2d RollingShutterCorrection(const ExposureSolution& solution,
                                                double line_delay_s,
                                                const Eigen::Vector2d& uv_dot) {
  Eigen::Matrix2d M = Eigen::Matrix2d::Identity();
  if (line_delay_s > 0.0 && !solution.at_lower_bound && !solution.at_upper_bound) {
    M.col(1) += (line_delay_s / solution.derivative) * uv_dot;
  }
  return M;
}

// d uv / d line_delay (file comment).
inline Eigen::Vector2d RollingShutterLineDelayJacobian(const ExposureSolution& solution,
                                                       int height,
                                                       const Eigen::Vector2d& uv_dot) {
  if (solution.at_lower_bound) return Eigen::Vector2d::Zero();
  if (solution.at_upper_bound) return uv_dot * static_cast<double>(height - 1);
  return uv_dot * (solution.row / solution.derivative);
}

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_ROLLING_SHUTTER_H_
