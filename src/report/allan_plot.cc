// allan.svg (report/allan_report.h): the measured curves with the decisions marked. Each
// identified term is a thick line over the averaging times that decided it; an unidentified white
// noise or random walk is drawn as its upper bound, dotted; the model fit is a thin grey line.
#include "splinecal/report/allan_report.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "splinecal/allan/allan.h"
#include "splinecal/allan/detail/sensor_units.h"
#include "splinecal/axis_name.h"
#include "splinecal/plot/svg_plot.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace {

using internal::SensorUnits;
using internal::UnitsOf;

const char* const kTermColors[kNumNoiseTerms] = {
    "#9467bd", "#d62728", "#ff7f0e", "#2ca02c", "#8c564b"};

// A term's line, adev = coefficient * sqrt(basis(tau)), from tau_lo to tau_hi (a few points: the
// slope is exact on log axes either way).
void AddTermLine(
    NoiseTerm term, double coefficient, double tau_lo, double tau_hi, plot::Series* line) {
  for (const double tau : {tau_lo, std::sqrt(tau_lo * tau_hi), tau_hi}) {
    line->x.push_back(tau);
    line->y.push_back(coefficient * std::sqrt(NoiseTermBasis(term, tau)));
  }
}

// The y range: the measured points in the upper part of the panel, room below them for the
// legend (kLegendRoom of the height); the lines are clipped to it.
void SetYRange(const plot::Series& measured, plot::Panel* panel) {
  constexpr double kLegendRoom = 0.45;
  double data_lo = 0.0;
  double data_hi = 0.0;
  for (size_t i = 0; i < measured.y.size(); ++i) {
    if (!(measured.y[i] > 0.0)) continue;
    const double low = measured.y_low[i] > 0.0 ? measured.y_low[i] : measured.y[i];
    data_lo = data_lo > 0.0 ? std::min(data_lo, low) : low;
    data_hi = std::max(data_hi, measured.y_high[i]);
  }
  if (data_lo > 0.0 && data_hi > data_lo) {
    const double span = std::log10(data_hi / data_lo);
    plot::AutoRange(data_lo / std::pow(10.0, span * kLegendRoom / (1.0 - kLegendRoom)),
                    data_hi,
                    plot::Scale::kLog,
                    &panel->y.min,
                    &panel->y.max);
  }
}

void AddAxisPanel(const AxisAllan& axis, bool unreliable, plot::Figure* figure) {
  const SensorUnits& units = UnitsOf(axis.sensor);
  const AllanCurve& curve = axis.curve;
  plot::Panel& panel = figure->panels.emplace_back();
  panel.title =
      std::string(axis.sensor == ImuSensor::kGyroscope ? "gyroscope " : "accelerometer ") +
      AxisName(axis.axis) + (unreliable ? " (UNRELIABLE: moving)" : "");
  panel.x = {"averaging time τ [s]", plot::Scale::kLog};
  panel.y = {std::string("Allan deviation [") + units.adev_svg + "]", plot::Scale::kLog};
  panel.legend = plot::LegendPosition::kBottomLeft;

  plot::Series& measured = panel.series.emplace_back();
  measured.label = "measured, 90% intervals (EDF)";
  measured.color = "#1f77b4";
  measured.marker = plot::Marker::kCircle;
  measured.marker_size = 2.0;
  measured.line_width = 1.0;
  measured.x = curve.tau_s;
  measured.y = curve.adev;
  measured.y_low = axis.fit.adev_low;
  measured.y_high = axis.fit.adev_high;
  SetYRange(measured, &panel);

  const double tau_lo = curve.tau_s.front();
  const double tau_hi = curve.tau_s.back();
  plot::Series& model = panel.series.emplace_back();
  model.label = "IEEE 952 model fit (second opinion)";
  model.color = "#7f7f7f";
  model.line_width = 0.8;
  for (const double tau : curve.tau_s) {
    model.x.push_back(tau);
    model.y.push_back(std::sqrt(axis.fit.model.AllanVariance(tau)));
  }

  for (int j = 0; j < kNumNoiseTerms; ++j) {
    const NoiseTerm term = static_cast<NoiseTerm>(j);
    const TermEstimate& estimate = axis.fit[term];
    const std::string symbol = std::string(1, "QNBKR"[j]);
    if (estimate.identified) {
      plot::Series& line = panel.series.emplace_back();
      line.label = StringPrintf("%s = %.3g %s: slope %.2f over %.3g-%.3g s",
                                symbol.c_str(),
                                estimate.value,
                                units.Of(term, true),
                                estimate.measured_slope,
                                estimate.tau_min_s,
                                estimate.tau_max_s);
      line.color = kTermColors[j];
      line.line_width = 3.0;
      AddTermLine(term, estimate.value, estimate.tau_min_s, estimate.tau_max_s, &line);
    } else if ((term == NoiseTerm::kWhite || term == NoiseTerm::kRandomWalk) &&
               std::isfinite(estimate.upper_bound)) {
      plot::Series& line = panel.series.emplace_back();
      line.label = StringPrintf("%s ≤ %.3g %s (upper bound: not identified)",
                                symbol.c_str(),
                                estimate.upper_bound,
                                units.Of(term, true));
      line.color = kTermColors[j];
      line.dashed = true;
      line.line_width = 1.0;
      AddTermLine(term, estimate.upper_bound, tau_lo, tau_hi, &line);
    }
  }
}

}  // namespace

std::string AllanSvgText(const AllanResult& result) {
  plot::Figure figure;
  figure.title = StringPrintf("Allan deviation: %lld samples, %.6g s at %.6g Hz%s",
                              static_cast<long long>(result.num_samples),
                              result.num_samples / result.rate_hz,
                              result.rate_hz,
                              result.motion.moving ? " — the recording MOVES" : "");
  int gyro_axes = 0;
  int accel_axes = 0;
  for (const AxisAllan& axis : result.axes) {
    (axis.sensor == ImuSensor::kGyroscope ? gyro_axes : accel_axes) += 1;
  }
  figure.columns = std::max(1, std::max(gyro_axes, accel_axes));
  for (const AxisAllan& axis : result.axes) AddAxisPanel(axis, result.motion.moving, &figure);
  return plot::RenderSvg(figure);
}

}  // namespace splinecal
