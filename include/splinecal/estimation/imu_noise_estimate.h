// The IMU noise a spline problem's residuals show, estimated between solver rounds by variance
// components (estimation/variance_components.h), as `calibrate` and `fit` do unless told to
// trust the given densities.
//
// Four groups: gyro and accelerometer white noise (the IMU residuals, sigma = density
// sqrt(rate)) and, with a bias spline, the gyro and accelerometer bias random walks (the prior
// between bias control points).
//   * The random walks are re-estimated and re-weighted (sigma_l *= sqrt(f_l)) where the data
//     determines them (redundancy >= VarianceComponentOptions::min_redundancy); otherwise they
//     keep the given density, and the estimate says so.
//   * The white noise is measured (density sqrt(f_l)) and enters the covariance
//     (MarginalCovarianceOptions::noise_factors: the estimate's covariance under the measured
//     noise). By default it does not re-weight the solve: on real data most of the excess is
//     vibration above the spline's bandwidth, and weighting the IMU down by it made the EuRoC
//     imu_april halves disagree more, not less (docs/calibrate.md, "How much to trust the
//     numbers"). ImuNoiseMode::kReweighted re-weights it too.
#ifndef SPLINECAL_ESTIMATION_IMU_NOISE_ESTIMATE_H_
#define SPLINECAL_ESTIMATION_IMU_NOISE_ESTIMATE_H_

#include <array>
#include <map>
#include <string>

#include "splinecal/estimation/imu_noise_mode.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/spline_problem.h"
#include "splinecal/estimation/variance_components.h"
#include "splinecal/imu/noise.h"

namespace splinecal {

// What a result reports about the IMU noise.
struct ImuNoiseEstimate {
  ImuNoiseMode mode = ImuNoiseMode::kEstimated;
  ImuNoise given;     // --imu-yaml, or the default ADIS16448
  ImuNoise used;      // the densities that weighted the final solve
  ImuNoise measured;  // what the residuals show (= used where not determined)
  // Per ImuResidualKind (gyro, accel, gyro random walk, accel random walk): residual rows,
  // redundancy r_l, and whether the data determined the density.
  std::array<int, kNumImuResidualKinds> num_residuals{};
  std::array<double, kNumImuResidualKinds> redundancy{};
  std::array<bool, kNumImuResidualKinds> determined{};
  int updates = 0;  // estimations done
  // measured / given per kind, in the order above.
  std::array<double, kNumImuResidualKinds> MeasuredOverGiven() const;
};

// Kalibr's key of each kind: gyroscope_noise_density, accelerometer_noise_density,
// gyroscope_random_walk, accelerometer_random_walk.
const char* ImuNoiseKey(ImuResidualKind kind);
// The density of `kind` in `noise`.
double ImuNoiseDensity(const ImuNoise& noise, ImuResidualKind kind);

class ImuNoiseEstimator {
 public:
  ImuNoiseEstimator(const ImuNoise& given, double imu_rate_hz, ImuNoiseMode mode);

  const ImuNoise& densities() const { return estimate_.used; }  // the weights
  double gyro_sigma() const { return estimate_.used.GyroWhiteStd(rate_hz_); }
  double accel_sigma() const { return estimate_.used.AccelWhiteStd(rate_hz_); }
  const ImuNoiseEstimate& estimate() const { return estimate_; }

  // Estimates the noise from `spline_problem`'s solved problem (every residual block not added
  // by it counts as one more group) and re-weights what the mode re-weights. Returns the
  // largest relative change of a weight's standard deviation, |sigma_new / sigma_old - 1| (0
  // when nothing was re-weighted or the estimate failed). num_threads: evaluating the residuals.
  double Update(SplineProblem* spline_problem, int num_threads = 1);

  // For MarginalCovarianceOptions: the group of a residual block of `spline_problem`, and the
  // variance factors (measured / used)^2 of the white-noise groups (empty for kGiven).
  static int GroupOf(const SplineProblem& spline_problem, ceres::ResidualBlockId id);
  std::map<int, double> NoiseFactors() const;

  // Sets in `options` what the reported standard deviations need beyond the weights: the
  // measured white noise (noise_factors, group_of) and the cluster-robust covariance over time
  // windows of robust_window_s (cluster_of; 0: none) of `spline_problem`, which must outlive the
  // computation. Returns whether it set anything (both need the Schur backend).
  bool AddToCovarianceOptions(const SplineProblem* spline_problem,
                              double robust_window_s,
                              MarginalCovarianceOptions* options) const;

 private:
  double rate_hz_;
  ImuNoiseEstimate estimate_;
};

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_NOISE_ESTIMATE_H_
