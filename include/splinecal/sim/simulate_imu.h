// IMU simulation from a spline T_w_s(t) (`splinecal simulate`), in the spline's own trajectory
// model (SE3Spline::model(), spline/trajectory_model.h).
//
// At every IMU time t_k the spline gives the pose, body rate w_s, world velocity and the body
// acceleration; the readings are the IMU model of imu/imu_model.h (docs/conventions.md, "IMU
// model") plus Kalibr noise from sim/noise_generator.h:
//
//     gyro_k  = w_s(t_k) + b_g,k + n_g,k
//     accel_k = R_w_s(t_k)^T (a_w(t_k) - g_w) + b_a,k + n_a,k,      g_w = (0, 0, -g)
//
// b_.,0 is the initial bias, then a random walk; n white noise (noise_generator.h). With
// noise_free the biases stay at their initial values and there is no white noise; with
// noise_free and zero biases every reading is bit for bit PredictImu (imu/imu_model.h) of the
// spline. Ground truth rows carry, at every IMU time, the spline's pose, world velocity
// dp_w_s/dt and the biases that were added to that reading.
//
// IMU times: t_k = start_ns + round(k * 1e9 / rate_hz) ns, k = 0, 1, ... while t_k <= end_ns
// (exact multiples for rates that divide 1e9 ns, e.g. 5 ms at 200 Hz; never accumulated, so no
// drift for other rates).
#ifndef SPLINECAL_SIM_SIMULATE_IMU_H_
#define SPLINECAL_SIM_SIMULATE_IMU_H_

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "splinecal/estimation/pose_fit.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/noise.h"
#include "splinecal/sim/trajectories.h"
#include "splinecal/io/euroc.h"
#include "splinecal/spline/se3_spline.h"

namespace splinecal {

struct SimulationOptions {
  double imu_rate_hz = 200.0;
  // Noise densities (Kalibr units); noise.update_rate_hz is ignored (imu_rate_hz is the rate).
  ImuNoise noise;
  bool noise_free = false;
  Eigen::Vector3d gyro_bias = Eigen::Vector3d::Zero();   // initial b_g [rad/s]
  Eigen::Vector3d accel_bias = Eigen::Vector3d::Zero();  // initial b_a [m/s^2]
  uint64_t seed = 0;
  double gravity_m_s2 = kDefaultGravity;  // g; g_w = (0, 0, -g)
};

// t_k = start_ns + round(k * 1e9 / rate_hz) for t_k <= end_ns. Throws splinecal::Error if
// rate_hz is not finite and positive, end_ns < start_ns, or there would be more than 1e9 samples.
std::vector<int64_t> ImuTimestamps(int64_t start_ns, int64_t end_ns, double rate_hz);

// Simulates IMU readings (and, if ground_truth is not nullptr, ground-truth rows) over
// [start_ns, end_ns]. Both outputs are replaced. Throws splinecal::Error if [start_ns, end_ns]
// is not inside the spline's valid range, for a bad rate or gravity, or for invalid noise.
void SimulateImu(const SE3Splined& spline,
                 int64_t start_ns,
                 int64_t end_ns,
                 const SimulationOptions& options,
                 std::vector<ImuSample>* imu,
                 std::vector<GroundTruthState>* ground_truth);

// The spline of an analytic trajectory over [start_ns, end_ns]: the knot layout
// KnotLayoutCovering(start_ns, end_ns, knot_spacing_ns) fitted (estimation/pose_fit.h) to poses
// sampled every pose_step_ns over the layout's whole valid range. The trajectory runs on its own
// clock, trajectory time = (t_ns - start_ns) * 1e-9 s. pose_step_ns = 0 means knot_spacing_ns /
// 10 (ten poses per knot interval). The result's position_rms_m / rotation_rms_deg are the fit
// quality to report. Throws splinecal::Error for knot_spacing_ns <= 0 or end_ns < start_ns.
PoseFitResult FitAnalyticTrajectory(const AnalyticTrajectory& trajectory,
                                    int64_t start_ns,
                                    int64_t end_ns,
                                    int64_t knot_spacing_ns,
                                    int64_t pose_step_ns = 0,
                                    const PoseFitOptions& options = {});

}  // namespace splinecal

#endif  // SPLINECAL_SIM_SIMULATE_IMU_H_
