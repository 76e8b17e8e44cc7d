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
// Each term is decided from the measured curve itself [IEEE952, annex C]: it is *identified* only
// where the measured deviation, with its confidence interval from the equivalent degrees of
// freedom of the overlapping estimator (allan/edf.h, [Riley08, section 5.3]; of the strided one
// where the curve says a point used every s-th start index, AllanCurve::strides), follows that
// term's slope over a stated range of averaging times. Precisely, for a term of slope s:
//  1. a line of slope s passes through the intervals (at `confidence`) of at least min_points
//     consecutive averaging times, computed with the EDF of that term's noise type
//     (allan/slope_lines.h);
//  2. over that range no line of a neighbouring slope (s - 1/2, s + 1/2) does: the data tells
//     this slope from the next, so a stretch whose intervals are too wide to tell (the long end of
//     a short record) identifies nothing;
//  3. the range sits where the term can dominate: quantization before the white-noise range,
//     white noise at the short end (after a filter dip), bias instability, random walk and rate
//     ramp after it; the random walk and the rate ramp, which grow without bound, must not be
//     followed by a significant fall (a Gauss-Markov bias rises like a random walk up to its
//     correlation time, then falls: it is no random walk); and a flat bias-instability range must
//     be wider than the bend between a -1/2 and a +1/2 line at its own interval width.
// The value is the line's weighted least-squares intercept, clamped into the intercepts that pass
// through every interval, read as the term's coefficient (N at tau = 1 s, K at tau = 3 s,
// B = floor / 0.664, Q = adev tau / sqrt(3), R = adev sqrt(2) / tau); its interval is that of
// the most precise point of the range. Otherwise the term is *not identified*: the reason says
// which rule failed, and its upper bound is reported instead.
//
// Upper bound of a term: the largest coefficient that no point's interval top (at
// bound_confidence) contradicts, min_i high_i / sqrt(basis(tau_i)) (every term's variance is at
// most the total). A filtered
// sensor's curve dips below the white-noise line at the shortest averaging times (the sensor's
// anti-alias or averaging filter removes high-frequency noise), so the points of that dip, and
// for the white noise every point before its range, are left out: the bound then holds. An
// identified value is never above its own bound.
//
// The full IEEE 952 model fit (weighted non-negative least squares on the variances, Lawson-
// Hanson) stays as a second opinion; where it disagrees with the slope lines, the term says so.
//
// Scale invariance: multiplying the signal by s multiplies every estimate by s exactly (up to
// rounding): intervals are relative, the decisions use logarithms only, the NNLS columns are
// normalised.
//
// References: [IEEE952] IEEE Std 952-1997, annex C; [Riley08] W. J. Riley, "Handbook of Frequency
// Stability Analysis", NIST SP 1065, 2008; [ElSheimy08] N. El-Sheimy, H. Hou, X. Niu, "Analysis
// and Modeling of Inertial Sensors Using Allan Variance", IEEE Trans. Instrum. Meas. 57(1), 2008;
// [LawsonHanson74] C. L. Lawson, R. J. Hanson, "Solving Least Squares Problems", 1974, ch. 23.
#ifndef SPLINECAL_ALLAN_NOISE_FIT_H_
#define SPLINECAL_ALLAN_NOISE_FIT_H_

#include <Eigen/Core>
#include <array>
#include <string>
#include <vector>

#include "splinecal/allan/allan_deviation.h"
#include "splinecal/allan/edf.h"

namespace splinecal {

// The terms of the IEEE 952 model, in this order everywhere (arrays, YAML).
enum class NoiseTerm { kQuantization = 0, kWhite, kBiasInstability, kRandomWalk, kRateRamp };
constexpr int kNumNoiseTerms = 5;

// "quantization", "noise_density", "bias_instability", "random_walk", "rate_ramp" (YAML keys).
const char* NoiseTermKey(NoiseTerm term);
// "quantization noise", "white noise", "bias instability", "random walk", "rate ramp".
const char* NoiseTermName(NoiseTerm term);

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

// The log-log slope of a term's Allan deviation: -1, -1/2, 0, +1/2, +1.
double NoiseTermSlope(NoiseTerm term);
// The power-law noise type whose EDF a term's intervals use (allan/edf.h).
PowerLawNoise NoiseTermNoiseType(NoiseTerm term);

// One term's estimate and where it came from.
struct TermEstimate {
  bool identified = false;
  double value = 0.0;      // when identified: the coefficient (units in the file comment)
  double value_low = 0.0;  // its interval at the fit's confidence
  double value_high = 0.0;
  std::string reason;  // when not identified: why (one sentence)
  // The averaging times the estimate used, and the curve's own least-squares slope over them.
  double tau_min_s = 0.0;
  double tau_max_s = 0.0;
  int num_points = 0;
  double measured_slope = 0.0;
  // The largest coefficient no point contradicts (see the file comment); infinity when no point
  // is usable.
  double upper_bound = 0.0;
  // Where the model fit disagrees with this estimate; empty when it agrees.
  std::string model_note;
};

struct NoiseFitOptions {
  // Two-sided confidence of the intervals the decisions use.
  double confidence = 0.9;
  // Confidence of the interval tops the upper bounds use: higher, so that one point at the long
  // end that falls low by chance (1 in 10 at 90%) neither drags a bound below the truth nor
  // contradicts an identified value.
  double bound_confidence = 0.99;
  int min_points = 3;  // averaging times needed in a range
  // Model fit: floor of a point's relative error, standing for model error (anti-alias filters,
  // temperature) that the counting error ignores at short tau; re-weighting passes.
  double min_relative_error = 0.01;
  int reweight_iterations = 2;
};

struct AxisNoiseFit {
  // Slope-line estimates, one per term (Kalibr's keys use kWhite and kRandomWalk).
  std::array<TermEstimate, kNumNoiseTerms> terms;
  const TermEstimate& operator[](NoiseTerm term) const { return terms[static_cast<int>(term)]; }
  TermEstimate& operator[](NoiseTerm term) { return terms[static_cast<int>(term)]; }

  // The averaging times up to which the curve dips below the white-noise line (a filtered
  // sensor); 0 when it does not.
  double filter_dip_tau_s = 0.0;
  // Each point's interval at the fit's confidence, with the EDF of the noise type that the model
  // fit says dominates there (for plots and allan.csv).
  std::vector<double> adev_low;
  std::vector<double> adev_high;

  // The weighted least-squares fit of the whole model. A term counts as identified when it
  // holds at least half of the model variance at some measured averaging time.
  NoiseModel model;
  std::array<TermEstimate, kNumNoiseTerms> model_terms;
  // Root mean square of log(model adev / measured adev) over the curve (a fit-quality figure).
  double model_rms_log_error = 0.0;
};

// The confidence intervals FitNoise gives its points, relative to the deviation: for each noise
// type a term uses and each of the two confidences, point i's interval of a deviation of 1
// (allan/edf.h; times adev, the same bits as AllanDeviationInterval(adev, ...)). They depend on N,
// m and the stride only, so the axes of one recording share one table: its chi-square quantiles
// are nearly all of the fit's time at 1000 averaging times per decade (0.07 s per axis of 10^7
// samples).
class FitIntervals {
 public:
  // For curves of num_samples samples at these cluster sizes and strides (empty: all 1). Throws
  // splinecal::Error when a confidence of the options is not in (0, 1).
  FitIntervals(int64_t num_samples,
               const std::vector<int64_t>& cluster_sizes,
               const std::vector<int64_t>& strides,
               const NoiseFitOptions& options);

  // Whether a curve has the samples, sizes and strides of this table.
  bool Fits(const AllanCurve& curve) const;
  // Point i's interval for a deviation of 1, the noise type of `term`, at the options'
  // confidence (bound = false) or bound_confidence.
  const DeviationInterval& Relative(NoiseTerm term, bool bound, size_t i) const;

 private:
  int64_t num_samples_;
  std::vector<int64_t> cluster_sizes_;
  std::vector<int64_t> strides_;
  // [bound][noise type][point]; only the types NoiseTermNoiseType gives are filled.
  std::array<std::array<std::vector<DeviationInterval>, 5>, 2> relative_;
};

// Fits the noise terms of one axis. Throws splinecal::Error when the curve has fewer than 2
// averaging times with a positive deviation. `intervals` (optional, made with the same options)
// saves computing them again for each axis of a recording; it must fit the curve.
AxisNoiseFit FitNoise(const AllanCurve& curve,
                      const NoiseFitOptions& options = {},
                      const FitIntervals* intervals = nullptr);

// The IEEE 952 model alone (the second opinion inside FitNoise): fills model, model_terms and
// model_rms_log_error from the points with a positive deviation.
void FitNoiseModel(const AllanCurve& curve, const NoiseFitOptions& options, AxisNoiseFit* fit);

// Non-negative least squares: argmin |A x - b| subject to x >= 0 (Lawson-Hanson). Columns are
// scaled internally; `A` needs full column rank on its active set (terms that are exactly
// collinear stay at zero).
Eigen::VectorXd NonNegativeLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_NOISE_FIT_H_
