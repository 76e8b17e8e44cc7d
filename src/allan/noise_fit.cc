// The noise-term decisions of allan/noise_fit.h: slope lines through EDF confidence intervals.
#include "splinecal/allan/noise_fit.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/allan/slope_lines.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();
// A filter dip is looked for only up to this cluster size: anti-alias and averaging filters of
// IMUs act over a few to a few tens of samples, and a curve that still rises beyond that rises
// for another reason (a random walk that dominates from the start).
constexpr int64_t kMaxDipClusterSize = 100;

struct Points {
  std::vector<double> tau;
  std::vector<double> adev;
  std::vector<int64_t> m;
  std::vector<int64_t> stride;  // of the start indices (allan/work_budget.h)
  std::vector<size_t> index;    // in the curve
  int64_t num_samples = 0;
  int size() const { return static_cast<int>(tau.size()); }
};

// The stride of point i; a curve built by hand has none: every start index.
int64_t StrideOf(const AllanCurve& curve, size_t i) {
  return curve.strides.empty() ? 1 : curve.strides.at(i);
}

std::string Seconds(double tau_s) { return StringPrintf("%.3g s", tau_s); }

std::string SlopeText(double slope) {
  if (slope == -1.0) return "-1";
  if (slope == -0.5) return "-1/2";
  if (slope == 0.0) return "0";
  if (slope == 0.5) return "+1/2";
  return "+1";
}

// The curve with each point's interval from `term`'s EDF (allan/edf.h; the relative intervals
// from `intervals`, at its confidence or its bound confidence). weight: 1 / variance of
// ln(adev) ~ 2 edf (ln of a chi-square with edf degrees of freedom over edf has variance ~ 2 /
// edf; ln adev is half of it).
std::vector<LogPoint> IntervalsFor(NoiseTerm term,
                                   const Points& p,
                                   const FitIntervals& intervals,
                                   bool bound) {
  std::vector<LogPoint> points(p.size());
  for (int i = 0; i < p.size(); ++i) {
    const double edf =
        StridedAllanEdf(NoiseTermNoiseType(term), p.num_samples, p.m[i], p.stride[i]);
    const DeviationInterval& relative = intervals.Relative(term, bound, p.index[i]);
    points[i] = {std::log(p.tau[i]),
                 std::log(p.adev[i]),
                 std::log(p.adev[i] * relative.low),
                 std::log(p.adev[i] * relative.high),
                 2.0 * edf};
  }
  return points;
}

// The terms of longer averaging times, judged on the curve without the identified white noise:
// the IEEE 952 terms add in variance, so AVAR - N^2 / tau is what the others hold. Near the
// crossover white noise still adds 5-15% to the deviation; left in, it would tilt the random
// walk's line up. The absolute uncertainty of AVAR stays, so each interval's log-width grows by
// AVAR / (AVAR - N^2 / tau). Points where white noise holds more than kMaxWhiteShare of the
// variance are left out: returns the first point, at or after `begin`, from which all are kept.
constexpr double kMaxWhiteShare = 0.5;
int WithoutWhiteNoise(const Points& p, double n, int begin, std::vector<LogPoint>* points) {
  int first = static_cast<int>(points->size());
  for (int i = static_cast<int>(points->size()) - 1; i >= begin; --i) {
    const double total = p.adev[i] * p.adev[i];
    const double rest = total - n * n * NoiseTermBasis(NoiseTerm::kWhite, p.tau[i]);
    if (rest < (1.0 - kMaxWhiteShare) * total) break;
    LogPoint& point = (*points)[i];
    const double widen = total / rest;
    const double log_rest = 0.5 * std::log(rest);
    point.log_low = log_rest - widen * (point.log_adev - point.log_low);
    point.log_high = log_rest + widen * (point.log_high - point.log_adev);
    point.log_adev = log_rest;
    point.weight /= widen * widen;
    first = i;
  }
  return first;
}

// A term's coefficient from the intercept c of its line ln adev = c + s ln tau: the line's
// deviation at tau = 1 s over the basis' there (NoiseTermBasis(term, tau) ~ tau^(2 s)).
double Coefficient(NoiseTerm term, double c) {
  return std::exp(c) / std::sqrt(NoiseTermBasis(term, 1.0));
}

// The leading points where adev sqrt(tau) rises beyond the intervals: below the white-noise line.
int FilterDipEnd(const std::vector<LogPoint>& white, const Points& p) {
  int end = 0;
  while (end + 1 < p.size() && p.m[end + 1] <= kMaxDipClusterSize &&
         white[end].log_high + 0.5 * white[end].log_tau <
             white[end + 1].log_low + 0.5 * white[end + 1].log_tau) {
    ++end;
  }
  return end;  // points [0, end) are the dip; point `end` is the first above it
}

// Why a window was not taken (first failing rule), for the reason text.
enum class Failure { kNone, kNoWindow, kNoDiscrimination, kRule };

struct Decision {
  bool found = false;
  PointWindow window;
  double c = 0.0;  // intercept
  double c_low = 0.0;
  double c_high = 0.0;
  Failure failure = Failure::kNoWindow;
  PointWindow failed_window;  // the window the failure refers to
  double failed_slope = 0.0;  // the neighbouring slope that also fits (kNoDiscrimination)
  std::string rule;           // the rule that failed (kRule)
};

// An extra rule on a window that fits and discriminates: empty when it passes, else why not.
using WindowRule = std::string (*)(const std::vector<LogPoint>&, PointWindow, double slope);

// The random walk and the rate ramp grow without bound: no later point may lie significantly
// below the line's value at the end of the range.
std::string NoFallAfter(const std::vector<LogPoint>& points, PointWindow window, double slope) {
  double c_low = 0.0;
  double c_high = 0.0;
  LineFitsWindow(points, window, slope, &c_low, &c_high);
  const double c = WeightedIntercept(points, window, slope, c_low, c_high);
  const double level_at_end = c + slope * points[window.last].log_tau;
  for (int j = window.last + 1; j < static_cast<int>(points.size()); ++j) {
    if (points[j].log_high < level_at_end) {
      return StringPrintf(
          "the curve falls after its %s stretch %s to %s (at %s it is below the stretch's end "
          "beyond its interval): a correlated bias (Gauss-Markov), not a term that keeps growing",
          SlopeText(slope).c_str(),
          Seconds(std::exp(points[window.first].log_tau)).c_str(),
          Seconds(std::exp(points[window.last].log_tau)).c_str(),
          Seconds(std::exp(points[j].log_tau)).c_str());
    }
  }
  return "";
}

// A flat floor must be wider than the bend of a -1/2 and a +1/2 line, which looks flat, within
// intervals of relative width rho_high / rho_low, over 2 acosh((rho_high / rho_low)^2) / ln 10
// decades (the sum N^2 / tau + K^2 tau / 3 is proportional to cosh(ln(tau / tau_min))).
std::string WiderThanBend(const std::vector<LogPoint>& points, PointWindow window, double) {
  double widest = 0.0;
  for (int i = window.first; i <= window.last; ++i) {
    widest = std::max(widest, points[i].log_high - points[i].log_low);
  }
  const double bend_decades = 2.0 * std::acosh(std::exp(2.0 * widest)) / std::log(10.0);
  const double span = SpanDecades(points, window);
  if (span > bend_decades) return "";
  return StringPrintf(
      "flat only from %s to %s (%.2f decades), no wider than the bend between a -1/2 and a +1/2 "
      "line within these intervals (%.2f decades)",
      Seconds(std::exp(points[window.first].log_tau)).c_str(),
      Seconds(std::exp(points[window.last].log_tau)).c_str(),
      span,
      bend_decades);
}

enum class Choice { kEarliestThenLongest, kLongest, kLowest };

// The windows of `term`'s slope among points [begin, end) that fit, tell the slope from its
// neighbours and pass `rule`, and the one chosen.
Decision Decide(NoiseTerm term,
                const std::vector<LogPoint>& points,
                int begin,
                int end,
                int min_points,
                WindowRule rule,
                Choice choice) {
  const double slope = NoiseTermSlope(term);
  std::vector<double> neighbours;
  if (slope > -1.0) neighbours.push_back(slope - 0.5);
  if (slope < 1.0) neighbours.push_back(slope + 0.5);
  Decision decision;
  std::vector<PointWindow> accepted;
  for (const PointWindow& window : MaximalLineWindows(points, begin, end, slope, min_points)) {
    bool tells = true;
    for (const double other : neighbours) {
      if (LineFitsWindow(points, window, other)) {
        tells = false;
        if (decision.failure == Failure::kNoWindow ||
            (decision.failure == Failure::kNoDiscrimination &&
             window.size() > decision.failed_window.size())) {
          decision.failure = Failure::kNoDiscrimination;
          decision.failed_window = window;
          decision.failed_slope = other;
        }
        break;
      }
    }
    if (!tells) continue;
    const std::string broken = rule == nullptr ? "" : rule(points, window, slope);
    if (!broken.empty()) {
      decision.failure = Failure::kRule;
      decision.failed_window = window;
      decision.rule = broken;
      continue;
    }
    accepted.push_back(window);
  }
  if (accepted.empty()) return decision;
  PointWindow best = accepted.front();
  for (const PointWindow& window : accepted) {
    switch (choice) {
      case Choice::kEarliestThenLongest:
        // Windows that start inside the earliest one: the longest (it skips points that a filter
        // still pulls below the line).
        if (window.first <= accepted.front().last &&
            SpanDecades(points, window) > SpanDecades(points, best)) {
          best = window;
        }
        break;
      case Choice::kLongest:
        if (SpanDecades(points, window) > SpanDecades(points, best)) best = window;
        break;
      case Choice::kLowest: {
        double low_best = 0.0, high_best = 0.0, low = 0.0, high = 0.0;
        LineFitsWindow(points, best, slope, &low_best, &high_best);
        LineFitsWindow(points, window, slope, &low, &high);
        if (WeightedIntercept(points, window, slope, low, high) <
            WeightedIntercept(points, best, slope, low_best, high_best)) {
          best = window;
        }
        break;
      }
    }
  }
  decision.found = true;
  decision.failure = Failure::kNone;
  decision.window = best;
  LineFitsWindow(points, best, slope, &decision.c_low, &decision.c_high);
  decision.c = WeightedIntercept(points, best, slope, decision.c_low, decision.c_high);
  return decision;
}

// The not-identified reason of a decision.
std::string Reason(NoiseTerm term,
                   const Decision& decision,
                   const std::vector<LogPoint>& points,
                   int begin,
                   int end,
                   const NoiseFitOptions& options) {
  const std::string slope = SlopeText(NoiseTermSlope(term));
  const std::string confidence = StringPrintf("%.0f%%", 100.0 * options.confidence);
  auto tau = [&](int i) { return Seconds(std::exp(points[i].log_tau)); };
  switch (decision.failure) {
    case Failure::kNone:
      return "";
    case Failure::kNoWindow: {
      if (end - begin < options.min_points) {
        return StringPrintf(
            "fewer than %d averaging times left where %s can show (beyond the white-noise range, "
            "where white noise holds less than half the variance): record longer",
            options.min_points,
            NoiseTermName(term));
      }
      // The curve's own slope over the decade where the term would have to show.
      const bool long_end = NoiseTermSlope(term) > 0.0;
      int first = begin;
      int last = end - 1;
      const double decade = std::log(10.0);
      if (long_end) {
        while (first + 1 < last && points[last].log_tau - points[first].log_tau > decade) ++first;
      } else {
        while (last - 1 > first && points[last].log_tau - points[first].log_tau > decade) --last;
      }
      return StringPrintf(
          "no %d consecutive averaging times from %s to %s follow slope %s within their %s "
          "intervals (the measured slope from %s to %s is %.2f)",
          options.min_points,
          tau(begin).c_str(),
          tau(end - 1).c_str(),
          slope.c_str(),
          confidence.c_str(),
          tau(first).c_str(),
          tau(last).c_str(),
          MeasuredSlope(points, {first, last}));
    }
    case Failure::kNoDiscrimination:
      return StringPrintf(
          "from %s to %s the curve follows slope %s, but slope %s fits the %s intervals as well "
          "(too few clusters there to tell: record longer)",
          tau(decision.failed_window.first).c_str(),
          tau(decision.failed_window.last).c_str(),
          slope.c_str(),
          SlopeText(decision.failed_slope).c_str(),
          confidence.c_str());
    case Failure::kRule:
      return decision.rule;
  }
  return "";
}

// Fills one term's estimate from its decision; bound_begin is the first point its upper bound
// uses.
TermEstimate Estimate(NoiseTerm term,
                      const Decision& decision,
                      const std::vector<LogPoint>& points,
                      const std::vector<LogPoint>& bound_points,
                      int begin,
                      int end,
                      int bound_begin,
                      const NoiseFitOptions& options) {
  const double slope = NoiseTermSlope(term);
  TermEstimate estimate;
  estimate.upper_bound = kInfinity;
  for (int i = bound_begin; i < static_cast<int>(bound_points.size()); ++i) {
    estimate.upper_bound =
        std::min(estimate.upper_bound,
                 Coefficient(term, bound_points[i].log_high - slope * bound_points[i].log_tau));
  }
  if (!decision.found) {
    estimate.reason = Reason(term, decision, points, begin, end, options);
    return estimate;
  }
  const PointWindow w = decision.window;
  estimate.tau_min_s = std::exp(points[w.first].log_tau);
  estimate.tau_max_s = std::exp(points[w.last].log_tau);
  estimate.num_points = w.size();
  estimate.measured_slope = MeasuredSlope(points, w);
  if (Coefficient(term, decision.c_low) > estimate.upper_bound) {
    estimate.reason = StringPrintf(
        "from %s to %s the curve follows slope %s, but points after that lie below the line "
        "beyond their intervals",
        Seconds(estimate.tau_min_s).c_str(),
        Seconds(estimate.tau_max_s).c_str(),
        SlopeText(slope).c_str());
    return estimate;
  }
  estimate.identified = true;
  estimate.value = std::min(Coefficient(term, decision.c), estimate.upper_bound);
  // The interval of the most precise point of the range.
  int best = w.first;
  for (int i = w.first; i <= w.last; ++i) {
    if (points[i].weight > points[best].weight) best = i;
  }
  estimate.value_low = Coefficient(term, points[best].log_low - slope * points[best].log_tau);
  estimate.value_high = Coefficient(term, points[best].log_high - slope * points[best].log_tau);
  return estimate;
}

// Where the model fit's term disagrees with the slope line's.
std::string ModelNote(NoiseTerm term, const TermEstimate& slope_line, const TermEstimate& model) {
  // A difference inside the slope line's interval, or of a few percent (model error: the five
  // terms fit the whole curve at once), is no disagreement.
  constexpr double kMaterialDifference = 0.1;
  if (slope_line.identified && model.identified &&
      (model.value < slope_line.value_low || model.value > slope_line.value_high) &&
      std::abs(model.value / slope_line.value - 1.0) > kMaterialDifference) {
    return StringPrintf("the model fit gives %.4g, outside the slope line's interval [%.4g, %.4g]",
                        model.value,
                        slope_line.value_low,
                        slope_line.value_high);
  }
  if (slope_line.identified && !model.identified) {
    return std::string("the model fit gives ") + NoiseTermName(term) +
           " no range of its own: " + model.reason;
  }
  if (!slope_line.identified && model.identified) {
    return StringPrintf(
        "the model fit claims %.4g, dominant from %s to %s, but the measured curve does not "
        "follow slope %s there",
        model.value,
        Seconds(model.tau_min_s).c_str(),
        Seconds(model.tau_max_s).c_str(),
        SlopeText(NoiseTermSlope(term)).c_str());
  }
  return "";
}

}  // namespace

AxisNoiseFit FitNoise(const AllanCurve& curve,
                      const NoiseFitOptions& options,
                      const FitIntervals* intervals) {
  CHECK_EQ(curve.tau_s.size(), curve.adev.size());
  CHECK_EQ(curve.cluster_sizes.size(), curve.adev.size());
  if (!(options.confidence > 0.0 && options.confidence < 1.0)) {
    throw Error(StringPrintf("confidence must be in (0, 1), got %g", options.confidence));
  }
  AxisNoiseFit fit;
  FitNoiseModel(curve, options, &fit);  // throws for fewer than 2 usable points

  Points p;
  p.num_samples = curve.num_samples;
  for (size_t i = 0; i < curve.adev.size(); ++i) {
    if (!(curve.adev[i] > 0.0 && std::isfinite(curve.adev[i]) && curve.tau_s[i] > 0.0)) continue;
    p.tau.push_back(curve.tau_s[i]);
    p.adev.push_back(curve.adev[i]);
    p.m.push_back(curve.cluster_sizes[i]);
    p.stride.push_back(StrideOf(curve, i));
    p.index.push_back(i);
  }
  std::optional<FitIntervals> own_intervals;
  if (intervals == nullptr) {
    intervals =
        &own_intervals.emplace(curve.num_samples, curve.cluster_sizes, curve.strides, options);
  }
  CHECK(intervals->Fits(curve)) << "FitIntervals made for another curve";
  const int size = p.size();
  std::array<std::vector<LogPoint>, kNumNoiseTerms> points;
  std::array<std::vector<LogPoint>, kNumNoiseTerms> bound_points;
  for (int j = 0; j < kNumNoiseTerms; ++j) {
    points[j] = IntervalsFor(static_cast<NoiseTerm>(j), p, *intervals, false);
    bound_points[j] = IntervalsFor(static_cast<NoiseTerm>(j), p, *intervals, true);
  }
  auto of = [&](NoiseTerm term) -> const std::vector<LogPoint>& {
    return points[static_cast<int>(term)];
  };
  auto bounds_of = [&](NoiseTerm term) -> const std::vector<LogPoint>& {
    return bound_points[static_cast<int>(term)];
  };

  const int dip_end = FilterDipEnd(of(NoiseTerm::kWhite), p);
  fit.filter_dip_tau_s = dip_end > 0 ? p.tau[dip_end - 1] : 0.0;

  // Each term: the window Decide picks among points [begin, end), then its estimate there
  // (upper bounds from bound_begin on).
  auto decide = [&](NoiseTerm term, int begin, int end, WindowRule rule, Choice choice) {
    return Decide(term, of(term), begin, end, options.min_points, rule, choice);
  };
  auto estimate =
      [&](NoiseTerm term, const Decision& decision, int begin, int end, int bound_begin) {
        fit[term] =
            Estimate(term, decision, of(term), bounds_of(term), begin, end, bound_begin, options);
      };

  // White noise first: the others are placed relative to its range.
  const Decision white =
      decide(NoiseTerm::kWhite, dip_end, size, nullptr, Choice::kEarliestThenLongest);
  int after_white = white.found ? white.window.first + 1 : dip_end;
  estimate(NoiseTerm::kWhite, white, dip_end, size, white.found ? white.window.first : dip_end);
  if (fit[NoiseTerm::kWhite].identified) {
    const double n = fit[NoiseTerm::kWhite].value;
    int first = size;
    for (const NoiseTerm term :
         {NoiseTerm::kBiasInstability, NoiseTerm::kRandomWalk, NoiseTerm::kRateRamp}) {
      first = WithoutWhiteNoise(p, n, after_white, &points[static_cast<int>(term)]);
    }
    after_white = std::max(after_white, first);
  }
  const int quantization_end = white.found ? white.window.first : size;
  estimate(NoiseTerm::kQuantization,
           decide(NoiseTerm::kQuantization, 0, quantization_end, nullptr, Choice::kLongest),
           0,
           quantization_end,
           dip_end);
  estimate(NoiseTerm::kBiasInstability,
           decide(NoiseTerm::kBiasInstability, after_white, size, &WiderThanBend, Choice::kLowest),
           after_white,
           size,
           dip_end);
  const Decision walk =
      decide(NoiseTerm::kRandomWalk, after_white, size, &NoFallAfter, Choice::kLongest);
  estimate(NoiseTerm::kRandomWalk, walk, after_white, size, dip_end);
  const int after_walk =
      fit[NoiseTerm::kRandomWalk].identified ? walk.window.first + 1 : after_white;
  estimate(NoiseTerm::kRateRamp,
           decide(NoiseTerm::kRateRamp, after_walk, size, &NoFallAfter, Choice::kLongest),
           after_walk,
           size,
           dip_end);

  for (int j = 0; j < kNumNoiseTerms; ++j) {
    fit.terms[j].model_note =
        ModelNote(static_cast<NoiseTerm>(j), fit.terms[j], fit.model_terms[j]);
  }

  // Plot intervals: the EDF of the term the model says dominates at each point.
  fit.adev_low.assign(curve.adev.size(), 0.0);
  fit.adev_high.assign(curve.adev.size(), 0.0);
  for (size_t i = 0; i < curve.adev.size(); ++i) {
    if (!(curve.adev[i] > 0.0 && std::isfinite(curve.adev[i]))) continue;
    const auto variances = fit.model.TermVariances(curve.tau_s[i]);
    const int dominant =
        static_cast<int>(std::max_element(variances.begin(), variances.end()) - variances.begin());
    const DeviationInterval& relative =
        intervals->Relative(static_cast<NoiseTerm>(dominant), false, i);
    const DeviationInterval interval = {curve.adev[i] * relative.low,
                                        curve.adev[i] * relative.high};
    fit.adev_low[i] = interval.low;
    fit.adev_high[i] = interval.high;
  }
  return fit;
}

}  // namespace splinecal
