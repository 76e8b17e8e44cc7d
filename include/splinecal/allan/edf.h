// Confidence intervals of the overlapping Allan deviation from its equivalent degrees of freedom.
//
// The overlapping estimator averages N - 2m + 1 squared second differences, but they overlap, so
// they are far from independent: the estimate behaves like a scaled chi-square variable with
// `edf` degrees of freedom [Riley08, section 5.3],
//
//     edf * AVAR_measured / AVAR_true  ~  chi^2(edf),
//
// and edf depends on the noise type (how strongly neighbouring differences correlate) as well as
// on N and m. The interval of the true deviation at confidence c is then
//
//     [ adev sqrt(edf / chi^2_{(1+c)/2}(edf)),  adev sqrt(edf / chi^2_{(1-c)/2}(edf)) ].
//
// EDF uses the "simple" approximations of Howe, Allan and Barnes for the overlapping Allan
// variance [Riley08, section 5.3, table of simple EDF formulae], with M the number of phase
// (angle) points, M = N + 1 for N rate samples, and m the cluster size:
//
//     white PM   (alpha =  2):  (M + 1)(M - 2m) / (2 (M - m))
//     flicker PM (alpha =  1):  exp( sqrt( ln((M - 1) / (2m)) ln((2m + 1)(M - 1) / 4) ) )
//     white FM   (alpha =  0):  [3(M - 1)/(2m) - 2(M - 2)/M] 4m^2 / (4m^2 + 5)
//     flicker FM (alpha = -1):  2(M - 2) / (2.3 M - 4.9) for m = 1,  5 M^2 / (4m (M + 3m)) else
//     random-walk FM (-2):      (M - 2)/m ((M - 1)^2 - 3m(M - 1) + 4m^2) / (M - 3)^2
//
// A rate sensor's terms map onto these frequency-noise types (the rate is the "frequency", the
// integrated angle the "phase"): quantization noise is white PM, white rate noise N white FM,
// bias instability flicker FM, rate random walk K random-walk FM. The rate ramp (a drift, not a
// power-law noise) takes the random-walk FM value, the smallest EDF of the five at long averaging
// times, so its intervals are the widest, as they should be for a term read at the very end.
//
// Strided averaging times (allan/work_budget.h: every s-th start index, T = floor((N - 2m) / s) + 1
// terms) take
//
//     edf = min(EDF of the overlapping estimator at (N, m), T).
//
// Why: the second difference d_k = theta_{k+2m} - 2 theta_{k+m} + theta_k depends on the samples
// y_k .. y_{k+2m-1} for white FM, on the bias steps k+1 .. k+2m-1 for random-walk FM, and on the
// three phase points k, k+m, k+2m for white PM. For s >= 2m + 1 no two terms share any of these,
// so for these three noise types the terms are independent Gaussians of one variance and their
// mean of squares is exactly chi^2(T) / T: edf = T (the overlapping EDF is larger there, ~3N/(2m),
// ~N/m, ~N/2). For s << m consecutive terms are nearly the same, and leaving most of them out
// loses little: the strided sum estimates like the overlapping one (its EDF, below T). In between,
// for white FM, the exact EDF of a mean of T squared Gaussian terms with correlation rho is
//
//     edf = T^2 / sum_{i,j < T} rho((i - j) s)^2,
//     rho(j) = 1 - 3|j| / (2m) for |j| <= m,  (|j| - 2m) / (2m) for m <= |j| <= 2m,  0 beyond
//
// (d_k is the sum of y over [k+m, k+2m) minus that over [k, k+m); rho is the overlap of the two
// +-1 windows). Against it the rule is never pessimistic and at most 1.5 times optimistic: the
// worst ratio exact / rule, 2/3, is at s = m, where each term correlates with its neighbours by
// rho(m) = -1/2 and T = N / m < 3N / (2m) (edf_test.cc scans m = 1 .. 10^4, s = 1 .. 4096; the
// ratio is 1 for s >= 2m and above 0.92 for s <= m / 4). The 90% interval of ADEV is then up to
// sqrt(1.5) = 1.22 times too narrow at those few averaging times, where it is a fraction of a
// percent wide. Flicker PM and flicker FM terms correlate without sharing samples: there the rule
// is optimistic by an amount not measured (bias instability is read at m >> s).
//
// Chi-square quantiles are exact (the regularised incomplete gamma function, inverted), not the
// Wilson-Hilferty approximation, which is poor at the few degrees of freedom of the longest
// averaging times.
//
// [Riley08] W. J. Riley, "Handbook of Frequency Stability Analysis", NIST SP 1065, 2008;
// [AbramowitzStegun64] M. Abramowitz, I. A. Stegun, "Handbook of Mathematical Functions", 1964,
// 6.5.29 (series) and 6.5.31 (continued fraction) of the incomplete gamma function.
#ifndef SPLINECAL_ALLAN_EDF_H_
#define SPLINECAL_ALLAN_EDF_H_

#include <cstdint>

namespace splinecal {

// The power-law noise types of frequency-stability analysis, by alpha (the exponent of the
// rate's power spectral density, S_y(f) ~ f^alpha).
enum class PowerLawNoise { kWhitePm, kFlickerPm, kWhiteFm, kFlickerFm, kRandomWalkFm };

// Equivalent degrees of freedom of the overlapping Allan variance of num_samples rate samples at
// cluster size m (1 <= m <= num_samples / 2), at least kMinimumEdf.
double OverlappingAllanEdf(PowerLawNoise noise, int64_t num_samples, int64_t m);

// The EDF of the estimate from every stride-th start index (see the file comment); stride 1: the
// overlapping EDF itself.
double StridedAllanEdf(PowerLawNoise noise, int64_t num_samples, int64_t m, int64_t stride);

// The formulas can fall below 1 at m near N / 2; an estimate from a single difference still has
// about one degree of freedom.
constexpr double kMinimumEdf = 1.0;

// Regularised lower incomplete gamma function P(a, x) = gamma(a, x) / Gamma(a), a > 0, x >= 0.
double RegularizedGammaP(double a, double x);

// The p-quantile (0 < p < 1) of the chi-square distribution with dof > 0 degrees of freedom, to
// a relative accuracy of 1e-12.
double ChiSquareQuantile(double p, double dof);

// A two-sided confidence interval [low, high] of a deviation.
struct DeviationInterval {
  double low = 0.0;
  double high = 0.0;
};

// The interval of the true Allan deviation, given the measured one, its EDF and the confidence
// c in (0, 1) (see the file comment).
DeviationInterval AllanDeviationInterval(double adev, double edf, double confidence);

}  // namespace splinecal

#endif  // SPLINECAL_ALLAN_EDF_H_
