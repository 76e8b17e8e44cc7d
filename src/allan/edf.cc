#include "splinecal/allan/edf.h"

#include <glog/logging.h>
#include <math.h>  // lgamma_r: std::lgamma writes the global signgam, a data race across threads

#include <algorithm>
#include <cmath>
#include <limits>

#include "splinecal/allan/work_budget.h"

namespace splinecal {
namespace {

// log Gamma(a) for a > 0, thread-safe.
double LogGamma(double a) {
  int sign = 0;
  return ::lgamma_r(a, &sign);
}

// Series of P(a, x) [AbramowitzStegun64, 6.5.29]: gamma(a, x) = e^-x x^a sum_n x^n / (a (a+1)
// ... (a+n)); converges quickly for x < a + 1.
double GammaPSeries(double a, double x) {
  double term = 1.0 / a;
  double sum = term;
  for (int n = 1; n < 100000; ++n) {
    term *= x / (a + n);
    sum += term;
    if (std::abs(term) < std::abs(sum) * 1e-16) break;
  }
  return sum * std::exp(-x + a * std::log(x) - LogGamma(a));
}

// Continued fraction of Q(a, x) = 1 - P(a, x) [AbramowitzStegun64, 6.5.31], evaluated by the
// modified Lentz method; converges quickly for x >= a + 1.
double GammaQContinuedFraction(double a, double x) {
  constexpr double kTiny = 1e-300;
  double b = x + 1.0 - a;
  double c = 1.0 / kTiny;
  double d = 1.0 / b;
  double h = d;
  for (int i = 1; i < 100000; ++i) {
    const double an = -i * (i - a);
    b += 2.0;
    d = an * d + b;
    if (std::abs(d) < kTiny) d = kTiny;
    c = b + an / c;
    if (std::abs(c) < kTiny) c = kTiny;
    d = 1.0 / d;
    const double delta = d * c;
    h *= delta;
    if (std::abs(delta - 1.0) < 1e-16) break;
  }
  return std::exp(-x + a * std::log(x) - LogGamma(a)) * h;
}

// Wilson-Hilferty: (chi2 / k)^(1/3) is nearly normal, mean 1 - 2/(9k), variance 2/(9k). Used as
// the start of the Newton iteration, and alone beyond kExactDofLimit, where its relative error is
// below 1e-5 and the exact evaluation would need thousands of series terms per call.
double WilsonHilferty(double p, double dof) {
  // Standard normal quantile by Newton on erfc (a handful of iterations from z = 0).
  double z = 0.0;
  for (int i = 0; i < 60; ++i) {
    const double cdf = 0.5 * std::erfc(-z / std::sqrt(2.0));
    const double pdf = std::exp(-0.5 * z * z) / std::sqrt(2.0 * 3.14159265358979323846);
    const double step = (cdf - p) / std::max(pdf, 1e-300);
    z -= std::clamp(step, -2.0, 2.0);
    if (std::abs(step) < 1e-14) break;
  }
  const double a = 2.0 / (9.0 * dof);
  const double cube = std::max(1.0 - a + z * std::sqrt(a), 1e-3);
  return dof * cube * cube * cube;
}
constexpr double kExactDofLimit = 2000.0;

}  // namespace

double OverlappingAllanEdf(PowerLawNoise noise, int64_t num_samples, int64_t m) {
  CHECK_GE(m, 1);
  CHECK_LE(2 * m, num_samples);
  // M phase points for N rate samples [Riley08, section 5.3].
  const double M = static_cast<double>(num_samples) + 1.0;
  const double md = static_cast<double>(m);
  double edf = kMinimumEdf;
  switch (noise) {
    case PowerLawNoise::kWhitePm:
      edf = (M + 1.0) * (M - 2.0 * md) / (2.0 * (M - md));
      break;
    case PowerLawNoise::kFlickerPm: {
      const double first = std::log((M - 1.0) / (2.0 * md));
      const double second = std::log((2.0 * md + 1.0) * (M - 1.0) / 4.0);
      edf = first > 0.0 && second > 0.0 ? std::exp(std::sqrt(first * second)) : kMinimumEdf;
      break;
    }
    case PowerLawNoise::kWhiteFm:
      edf = (3.0 * (M - 1.0) / (2.0 * md) - 2.0 * (M - 2.0) / M) * 4.0 * md * md /
            (4.0 * md * md + 5.0);
      break;
    case PowerLawNoise::kFlickerFm:
      edf = m == 1 ? 2.0 * (M - 2.0) / (2.3 * M - 4.9) : 5.0 * M * M / (4.0 * md * (M + 3.0 * md));
      break;
    case PowerLawNoise::kRandomWalkFm:
      edf = (M - 2.0) / md * ((M - 1.0) * (M - 1.0) - 3.0 * md * (M - 1.0) + 4.0 * md * md) /
            ((M - 3.0) * (M - 3.0));
      break;
  }
  return std::isfinite(edf) ? std::max(edf, kMinimumEdf) : kMinimumEdf;
}

double StridedAllanEdf(PowerLawNoise noise, int64_t num_samples, int64_t m, int64_t stride) {
  const double overlapping = OverlappingAllanEdf(noise, num_samples, m);
  if (stride == 1) return overlapping;
  const double terms = static_cast<double>(AllanTermCount(num_samples, m, stride));
  return std::max(kMinimumEdf, std::min(overlapping, terms));
}

double RegularizedGammaP(double a, double x) {
  CHECK_GT(a, 0.0);
  if (x <= 0.0) return 0.0;
  if (x < a + 1.0) return GammaPSeries(a, x);
  return 1.0 - GammaQContinuedFraction(a, x);
}

double ChiSquareQuantile(double p, double dof) {
  CHECK(p > 0.0 && p < 1.0) << p;
  CHECK_GT(dof, 0.0);
  double x = WilsonHilferty(p, dof);
  if (dof > kExactDofLimit) return x;
  // Newton on F(x) = P(dof/2, x/2) - p with the chi-square density, kept inside a bracket that
  // bisection (on log x) shrinks whenever a Newton step leaves it.
  const double a = 0.5 * dof;
  double low = 0.0;
  double high = std::numeric_limits<double>::infinity();
  for (int i = 0; i < 200; ++i) {
    const double f = RegularizedGammaP(a, 0.5 * x) - p;
    if (f < 0.0) {
      low = x;
    } else {
      high = x;
    }
    const double log_density =
        (a - 1.0) * std::log(0.5 * x) - 0.5 * x - LogGamma(a) - std::log(2.0);
    const double step = f / std::exp(log_density);
    double next = x - step;
    if (!(next > low && next < high) || !std::isfinite(next)) {
      next = std::isfinite(high) ? (low > 0.0 ? std::sqrt(low * high) : 0.5 * high) : 2.0 * x;
    }
    if (std::abs(next - x) <= 1e-13 * x) return next;
    x = next;
  }
  return x;
}

DeviationInterval AllanDeviationInterval(double adev, double edf, double confidence) {
  CHECK(confidence > 0.0 && confidence < 1.0) << confidence;
  const double tail = 0.5 * (1.0 - confidence);
  DeviationInterval interval;
  interval.low = adev * std::sqrt(edf / ChiSquareQuantile(1.0 - tail, edf));
  interval.high = adev * std::sqrt(edf / ChiSquareQuantile(tail, edf));
  return interval;
}

}  // namespace splinecal
