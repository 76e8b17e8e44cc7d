// The options every continuous-time estimate shares, with one shape in fit and calibrate:
//
//   FitOptions / CalibrateOptions {
//     SplineModelOptions model;       what is estimated: knots, gravity, IMU noise, bias model
//     ...                             what only that estimate has (pose source, cameras, ...)
//     SolverOptions solver;           how it is solved (estimation/solve_rounds.h)
//     CovarianceOptions covariance;   how its standard deviations are computed
//   }
#ifndef SPLINECAL_ESTIMATION_OPTIONS_H_
#define SPLINECAL_ESTIMATION_OPTIONS_H_

#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/imu_noise_mode.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/noise.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {

// The continuous-time model of the IMU trajectory (estimation/spline_problem.h).
struct SplineModelOptions {
  // How the control poses are interpolated (spline/trajectory_model.h): the coupled SE(3) spline
  // (the conventions' spline, default) or the split SO(3) x R^3 spline (Kalibr's and basalt's
  // position spline; its accelerometer Jacobian costs less than half). Both share the control
  // poses, their parameter blocks and the orientation; docs/conventions.md says when to use which.
  TrajectoryModel trajectory = TrajectoryModel::kSE3;
  // Knot spacing dt [s] of the pose spline; 0 chooses it from the data (ChooseKnotSpacing,
  // estimation/knot_spacing.h) and says why.
  double knot_spacing_s = 0.0;
  // Gravity magnitude g [m/s^2]; g_w keeps this norm.
  double gravity_m_s2 = kDefaultGravity;
  // IMU noise, Kalibr densities. The weights use density * sqrt(rate) with the rate measured
  // from the IMU timestamps.
  ImuNoise noise;
  // The IMU noise from the residuals between solver rounds (variance components,
  // estimation/imu_noise_estimate.h), so that the standard deviations reflect the noise the
  // data shows; kGiven trusts `noise` as it is.
  ImuNoiseMode imu_noise = ImuNoiseMode::kEstimated;
  // Biases: constant, or a cubic B-spline with Kalibr's random-walk prior whose knots are
  // bias_knot_spacing_s apart (rounded to a whole number of pose knot intervals).
  BiasModel bias_model = BiasModel::kConstant;
  double bias_knot_spacing_s = 1.0;
};

// Standard deviations (estimation/marginal_covariance.h).
struct CovarianceOptions {
  bool compute = true;
  CovarianceBackend backend = CovarianceBackend::kAuto;
  // kAuto: ceres::Covariance up to this many compressed Jacobian entries, Schur above.
  double max_ceres_covariance_entries = 3e6;
  // Cluster-robust standard deviations over time windows of this length [s] (0: the noise
  // model's only): each reported std is the larger of the noise model's and the cluster-robust
  // one (estimation/marginal_covariance.h), so that model error and correlated noise the data
  // shows enter the error bars. Where it applies (calibrate, fit), it uses the Schur backend.
  double robust_window_s = 1.0;
  // With robust_window_s > 0 (intrinsics, calibrate): also the cluster-robust covariance over
  // kinds of target view (estimation/view_clusters.h), for model error that depends on the view;
  // each std is then the largest of the noise model's and the two sandwiches' where significant.
  bool view_clusters = true;
};

// Throws splinecal::Error, in plain words, for model values no estimate can use.
void CheckSplineModelOptions(const SplineModelOptions& model);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_OPTIONS_H_
