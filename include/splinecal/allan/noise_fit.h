// Noise terms of one sensor axis read off its Allan deviation curve.
//
// The IEEE Std 952 model of a rate sensor's Allan variance is a sum of five terms, each with its
// own log-log slope of the deviation [IEEE952, annex C], [ElSheimy08, table 1]:
//
//     AVAR(tau) = 3 Q^2 / tau^2          quantization noise Q        slope -1
//               + N^2 / tau              white noise density N       slope -1/2  (ADEV(1 s) = N)
//               + (2 ln 2 / pi) B^2      bias instability B          slope  0    (floor 0.664 B)
//               + K^2 tau / 3            random walk density K       slope +1/2  (ADEV(3 s) = K)
//               + R^2 tau^2 / 2          rate ramp R                 slope +1
//
// N and K are Kalibr's `*_noise_density` and `*_random_walk` (docs/conventions.md, "IMU model"):
// continuous-time densities, not per-sample standard deviations. Units for a gyroscope (an
// accelerometer: replace rad by m/s): Q [rad], N [rad/s/sqrt(Hz)], B [rad/s],
// K [rad/s^2/sqrt(Hz)], R [rad/s^2].
//
// Two estimates are made, as the issue asks:
//  1. The full model: a weighted non-negative least-squares fit of (Q^2, N^2, B^2, K^2, R^2) to
//     AVAR at every averaging time (the terms are linear in these), with weights from the error
//     bars (relative variance error 2 * adev_error / adev, floored at 2 * min_relative_error),
//     re-weighted twice with the fitted model in place of the noisy measurement so that points
//     that happen to fall low do not get too much weight. Solved by Lawson-Hanson active sets.
//  2. The slope lines (Kalibr's keys take these): each term is read only where it dominates,
//     i.e. where its share of the fitted model variance is at least `dominance` (0.9 for N, so
//     the other terms shift a point by at most 5% in deviation; 0.8 for K, see NoiseFitOptions):
//       N: the -1/2 slope line through those points (weighted mean of log(adev sqrt(tau))),
//          read at tau = 1 s;
//       K: the +1/2 slope line through its points (log(adev sqrt(3 / tau))), read at tau = 3 s;
//       B: the lowest deviation where B's share is at least `flat_dominance` (0.5), / 0.664.
//     A term whose region has fewer than min_points averaging times is reported as not
//     identifiable, with the reason, instead of a number that means nothing.
//
// Scale invariance: multiplying the signal by s multiplies every estimate by s exactly (up to
// rounding): the weights are relative, the regions depend on shares, the NNLS columns are
// normalised.
//
// References: [IEEE952] IEEE Std 952-1997, annex C; [ElSheimy08] N. El-Sheimy, H. Hou, X. Niu,
// "Analysis and Modeling of Inertial Sensors Using Allan Variance", IEEE Trans. Instrum. Meas.
// 57(1), 2008; [LawsonHanson74] C. L. Lawson, R. J. Hanson, "Solving Least Squares Problems",
// 1974, ch. 23 (NNLS).
#ifndef SPLINECAL_ALLAN_NOISE_FIT_H_
#define SPLINECAL_ALLAN_NOISE_FIT_H_

#include <Eigen/Core>
#include <array>
#include <string>

#include "splinecal/allan/allan_deviation.h"

namespace splinecal {

// The terms of the IEEE 952 model, in this order everywhere (arrays, YAML).
enum class NoiseTerm { kQuantization = 0, kWhite, kBiasInstability, kRandomWalk, kRateRamp };
constexpr int kNumNoiseTerms = 5;

// "quantization", "noise_density", "bias_instability", "random_walk", "rate_ramp" (YAML keys).
const char* NoiseTermKey(NoiseTerm term);

// The model's coefficients Q, N, B, K, R (all >= 0; see the file comment for units).
struct NoiseModel {
  std::array<double, kNumNoiseTerms> value = {0.0, 0.0, 0.0, 0.0, 0.0};

  double operator[](NoiseTerm term) const { return value[static_cast<int>(term)]; }
  double& operator[](NoiseTerm term) { return value[static_cast<int>(term)]; }

  // The model's Allan variance at tau [s] and each term's part of it.
  double AllanVariance(double tau_s) const;
  std::array<double, kNumNoiseTerms> TermVariances(double tau_s) const;
};

// AVAR(tau) of a term with coefficient 1: 3 / tau^2, 1 / tau, 2 ln 2 / pi, tau / 3, tau^2 / 2.
double NoiseTermBasis(NoiseTerm term, double tau_s);

// sqrt(2 ln 2 / pi) = 0.6643: the Allan deviation floor of a bias instability B is 0.664 B.
constexpr double kBiasInstabilityFloor = 0.6642824702679601;

// One estimate and where it came from.
struct TermEstimate {
  bool identified = false;
  double value = 0.0;  // when identified
  std::string reason;  // when not identified: why (one sentence)
  // The averaging times the estimate used.
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  int num_points = 0;
};

struct NoiseFitOptions {
  // Share of the model variance that makes a slope region. The random-walk region lies at the
  // long, noisy end of the curve, where a spurious rate-ramp term easily takes 10% of the fitted
  // variance (3 of 10 simulated 4-hour gyro records had no point with a 90% random-walk share),
  // so its threshold is lower; its points then overstate K by about 5% on average.
  double dominance = 0.9;              // white noise
  double random_walk_dominance = 0.8;  // random walk
  double flat_dominance = 0.5;         // share for the bias-instability floor
  int min_points = 3;                  // averaging times needed in a region
  // Floor of the relative error of a point, standing for model error (anti-alias filters,
  // temperature) that the counting error 1 / sqrt(2 (K - 1)) ignores at short tau.
  double min_relative_error = 0.01;
  int reweight_iterations = 2;
};

struct AxisNoiseFit {
  // Slope-line estimates (Kalibr's keys use noise_density and random_walk).
  TermEstimate noise_density;     // N: -1/2 line at tau = 1 s
  TermEstimate random_walk;       // K: +1/2 line at tau = 3 s
  TermEstimate bias_instability;  // B: floor / 0.664
  // Upper bounds that hold whatever dominates: the -1/2 and +1/2 lines below every point's
  // 2-sigma top, min over tau of adev (1 + 2 e) sqrt(tau) and adev (1 + 2 e) sqrt(3 / tau), with e
  // the relative error. Used when a slope line is not identifiable.
  double noise_density_upper_bound = 0.0;
  double random_walk_upper_bound = 0.0;

  // The weighted least-squares fit of the whole model. A term counts as identified when it
  // holds at least half of the model variance at some measured averaging time.
  NoiseModel model;
  std::array<TermEstimate, kNumNoiseTerms> model_terms;
  // Root mean square of log(model adev / measured adev) over the curve (a fit-quality figure).
  double model_rms_log_error = 0.0;
};

// Fits the noise terms of one axis. Throws splinecal::Error when the curve has fewer than 2
// averaging times with a positive deviation.
AxisNoiseFit FitNoise(const AllanCurve& curve, const NoiseFitOptions& options = {});

// Non-negative least squares: argmin |A x - b| subject to x >= 0 (Lawson-Hanson). Columns are
// scaled internally; `A` needs full column rank on its active set (terms that are exactly
// collinear stay at zero).
Eigen::VectorXd NonNegativeLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_NOISE_FIT_H_
