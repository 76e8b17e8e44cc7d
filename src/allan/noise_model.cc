#include <glog/logging.h>

#include <Eigen/QR>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "splinecal/allan/noise_fit.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

namespace splinecal {
namespace {

constexpr double kLn2 = 0.69314718055994530942;
// A model term must hold at least this share of the model variance at some averaging time to
// count as identified in the full fit.
constexpr double kModelIdentifiedShare = 0.5;

// Each term's names (for people; the YAML key), its Allan deviation slope (ADEV ~ tau^slope for
// AVAR ~ tau^(2 slope), NoiseTermBasis) and its power-law noise type (the rate is the
// "frequency", its integral the "phase", allan/edf.h), in NoiseTerm order.
struct NoiseTermProperties {
  const char* name;
  const char* key;
  double slope;
  PowerLawNoise noise_type;
};
constexpr std::array<NoiseTermProperties, kNumNoiseTerms> kNoiseTermProperties = {{
    {"quantization noise", "quantization", -1.0, PowerLawNoise::kWhitePm},
    {"white noise", "noise_density", -0.5, PowerLawNoise::kWhiteFm},
    {"bias instability", "bias_instability", 0.0, PowerLawNoise::kFlickerFm},
    {"random walk", "random_walk", 0.5, PowerLawNoise::kRandomWalkFm},
    {"rate ramp", "rate_ramp", 1.0, PowerLawNoise::kRandomWalkFm},
}};

const NoiseTermProperties& PropertiesOf(NoiseTerm term) {
  return kNoiseTermProperties.at(static_cast<size_t>(term));
}

std::string Percent(double fraction) { return StringPrintf("%.0f%%", 100.0 * fraction); }

// The averaging times where `term` holds at least `share` of the model variance.
std::vector<int> Region(const std::vector<std::array<double, kNumNoiseTerms>>& shares,
                        NoiseTerm term,
                        double share) {
  std::vector<int> region;
  for (size_t i = 0; i < shares.size(); ++i) {
    if (shares[i][static_cast<int>(term)] >= share) region.push_back(static_cast<int>(i));
  }
  return region;
}

double LargestShare(const std::vector<std::array<double, kNumNoiseTerms>>& shares, NoiseTerm term) {
  double largest = 0.0;
  for (const auto& s : shares) largest = std::max(largest, s[static_cast<int>(term)]);
  return largest;
}

}  // namespace

const char* NoiseTermName(NoiseTerm term) { return PropertiesOf(term).name; }

double NoiseTermSlope(NoiseTerm term) { return PropertiesOf(term).slope; }

PowerLawNoise NoiseTermNoiseType(NoiseTerm term) { return PropertiesOf(term).noise_type; }

const char* NoiseTermKey(NoiseTerm term) { return PropertiesOf(term).key; }

double NoiseTermBasis(NoiseTerm term, double tau_s) {
  switch (term) {
    case NoiseTerm::kQuantization:
      return 3.0 / (tau_s * tau_s);
    case NoiseTerm::kWhite:
      return 1.0 / tau_s;
    case NoiseTerm::kBiasInstability:
      return 2.0 * kLn2 / kPi;
    case NoiseTerm::kRandomWalk:
      return tau_s / 3.0;
    case NoiseTerm::kRateRamp:
      return 0.5 * tau_s * tau_s;
  }
  return 0.0;
}

std::array<double, kNumNoiseTerms> NoiseModel::TermVariances(double tau_s) const {
  std::array<double, kNumNoiseTerms> variances;
  for (int j = 0; j < kNumNoiseTerms; ++j) {
    variances[j] = value[j] * value[j] * NoiseTermBasis(static_cast<NoiseTerm>(j), tau_s);
  }
  return variances;
}

double NoiseModel::AllanVariance(double tau_s) const {
  double total = 0.0;
  for (const double v : TermVariances(tau_s)) total += v;
  return total;
}

Eigen::VectorXd NonNegativeLeastSquares(const Eigen::MatrixXd& A, const Eigen::VectorXd& b) {
  CHECK_EQ(A.rows(), b.size());
  const int n = static_cast<int>(A.cols());
  // Unit-norm columns: the tolerances below are then relative, and scaling a column (a unit
  // change of one coefficient) does not change the solution path.
  Eigen::VectorXd scale(n);
  Eigen::MatrixXd As = A;
  for (int j = 0; j < n; ++j) {
    scale[j] = A.col(j).norm();
    if (scale[j] > 0.0 && std::isfinite(scale[j])) As.col(j) /= scale[j];
  }
  const double tolerance = 1e-12 * std::max(b.norm(), std::numeric_limits<double>::min());
  Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
  std::vector<bool> passive(n, false);
  const int max_outer = 3 * n + 10;
  for (int outer = 0; outer < max_outer; ++outer) {
    // [LawsonHanson74, ch. 23, steps 2-5]: the gradient w; the most promising free variable.
    const Eigen::VectorXd w = As.transpose() * (b - As * x);
    int best = -1;
    for (int j = 0; j < n; ++j) {
      if (passive[j] || !(scale[j] > 0.0 && std::isfinite(scale[j]))) continue;
      if (w[j] > tolerance && (best < 0 || w[j] > w[best])) best = j;
    }
    if (best < 0) break;
    passive[best] = true;
    // Steps 6-11: least squares on the passive set; step back while it leaves the feasible set.
    for (int inner = 0; inner < 3 * n + 10; ++inner) {
      std::vector<int> columns;
      for (int j = 0; j < n; ++j) {
        if (passive[j]) columns.push_back(j);
      }
      Eigen::MatrixXd Ap(As.rows(), static_cast<Eigen::Index>(columns.size()));
      for (size_t c = 0; c < columns.size(); ++c) Ap.col(c) = As.col(columns[c]);
      const Eigen::VectorXd zp = Ap.colPivHouseholderQr().solve(b);
      Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
      for (size_t c = 0; c < columns.size(); ++c) z[columns[c]] = zp[c];
      bool feasible = true;
      for (const int j : columns) feasible = feasible && z[j] > 0.0;
      if (feasible) {
        x = z;
        break;
      }
      double alpha = 1.0;
      for (const int j : columns) {
        if (z[j] <= 0.0) alpha = std::min(alpha, x[j] / (x[j] - z[j]));
      }
      x += alpha * (z - x);
      for (const int j : columns) {
        if (x[j] <= 0.0 || (z[j] <= 0.0 && x[j] <= tolerance)) {
          x[j] = 0.0;
          passive[j] = false;
        }
      }
    }
  }
  for (int j = 0; j < n; ++j) {
    x[j] = (scale[j] > 0.0 && std::isfinite(scale[j])) ? x[j] / scale[j] : 0.0;
  }
  return x;
}

void FitNoiseModel(const AllanCurve& curve, const NoiseFitOptions& options, AxisNoiseFit* out) {
  CHECK_EQ(curve.tau_s.size(), curve.adev.size());
  CHECK_EQ(curve.adev_error.size(), curve.adev.size());
  // The usable points: positive, finite deviations (a log-log fit cannot use zeros).
  std::vector<double> tau;
  std::vector<double> adev;
  std::vector<double> relative;
  for (size_t i = 0; i < curve.adev.size(); ++i) {
    if (!(curve.adev[i] > 0.0 && std::isfinite(curve.adev[i]) && curve.tau_s[i] > 0.0)) continue;
    tau.push_back(curve.tau_s[i]);
    adev.push_back(curve.adev[i]);
    const double r = curve.adev_error[i] / curve.adev[i];
    relative.push_back(std::isfinite(r) ? std::max(r, options.min_relative_error) : 1.0);
  }
  const int m = static_cast<int>(tau.size());
  if (m < 2) {
    throw Error("Allan deviation has " + std::to_string(m) +
                " averaging times with a positive value; the noise fit needs at least 2");
  }

  AxisNoiseFit& fit = *out;
  // 1. Weighted NNLS on the variances, c_j = (Q^2, N^2, B^2, K^2, R^2).
  std::vector<double> reference(m);
  for (int i = 0; i < m; ++i) reference[i] = adev[i] * adev[i];
  Eigen::VectorXd c = Eigen::VectorXd::Zero(kNumNoiseTerms);
  for (int iteration = 0; iteration <= options.reweight_iterations; ++iteration) {
    Eigen::MatrixXd A(m, kNumNoiseTerms);
    Eigen::VectorXd b(m);
    for (int i = 0; i < m; ++i) {
      // Var(AVAR estimate) ~ (2 * relative error of ADEV * AVAR)^2.
      const double sigma = 2.0 * relative[i] * reference[i];
      for (int j = 0; j < kNumNoiseTerms; ++j) {
        A(i, j) = NoiseTermBasis(static_cast<NoiseTerm>(j), tau[i]) / sigma;
      }
      b[i] = adev[i] * adev[i] / sigma;
    }
    c = NonNegativeLeastSquares(A, b);
    for (int i = 0; i < m; ++i) {
      double model = 0.0;
      for (int j = 0; j < kNumNoiseTerms; ++j) {
        model += c[j] * NoiseTermBasis(static_cast<NoiseTerm>(j), tau[i]);
      }
      if (model > 0.0) reference[i] = model;
    }
  }
  for (int j = 0; j < kNumNoiseTerms; ++j) fit.model.value[j] = std::sqrt(std::max(c[j], 0.0));

  std::vector<std::array<double, kNumNoiseTerms>> shares(m);
  double sum_squared_log = 0.0;
  for (int i = 0; i < m; ++i) {
    const auto variances = fit.model.TermVariances(tau[i]);
    double total = 0.0;
    for (const double v : variances) total += v;
    for (int j = 0; j < kNumNoiseTerms; ++j)
      shares[i][j] = total > 0.0 ? variances[j] / total : 0.0;
    const double log_error = total > 0.0 ? 0.5 * std::log(total / (adev[i] * adev[i])) : 0.0;
    sum_squared_log += log_error * log_error;
  }
  fit.model_rms_log_error = std::sqrt(sum_squared_log / m);

  for (int j = 0; j < kNumNoiseTerms; ++j) {
    const NoiseTerm term = static_cast<NoiseTerm>(j);
    TermEstimate& estimate = fit.model_terms[j];
    const std::vector<int> region = Region(shares, term, kModelIdentifiedShare);
    if (fit.model.value[j] > 0.0 && !region.empty()) {
      estimate.identified = true;
      estimate.value = fit.model.value[j];
      estimate.tau_min_s = tau[region.front()];
      estimate.tau_max_s = tau[region.back()];
      estimate.num_points = static_cast<int>(region.size());
    } else if (fit.model.value[j] == 0.0) {
      estimate.reason =
          std::string("the fit needs no ") + NoiseTermName(term) + " (its coefficient is 0)";
    } else {
      estimate.reason = std::string(NoiseTermName(term)) + " holds at most " +
                        Percent(LargestShare(shares, term)) +
                        " of the fitted variance at any averaging time";
    }
  }
}

}  // namespace splinecal
