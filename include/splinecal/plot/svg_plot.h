// A small SVG plot writer shared by every splinecal command that draws: Allan deviation log-log
// plots with error bars (`splinecal allan`), top-view XY trajectories (`splinecal integrate`),
// time series of residuals (`splinecal fit`).
//
// A Figure is a grid of Panels; a Panel has two axes (linear or log) and Series of lines and/or
// point markers, each with optional vertical error bars. The writer chooses the axis ranges from
// the data unless they are given, puts ticks at round values (1, 2, 5 x 10^k on linear axes,
// every decade on log axes, with unlabelled minor ticks at 2..9 x 10^k) and draws a legend.
//
// Guarantees:
//   - Deterministic: the same Figure gives the same bytes (no clock, no randomness, numbers
//     printed with a fixed format in the "C" locale conventions of snprintf).
//   - Never writes NaN or inf: non-finite points are skipped (a line is broken there), and so are
//     points <= 0 on a log axis. Segments are clipped to the plot area, so a point far outside a
//     given axis range does not produce huge coordinates.
//   - Text is XML-escaped; the output is a standalone SVG 1.1 document in UTF-8.
//
// Example (a log-log plot with error bars):
//
//   plot::Figure figure;
//   figure.title = "Allan deviation";
//   plot::Panel& panel = figure.panels.emplace_back();
//   panel.x = {"averaging time tau [s]", plot::Scale::kLog};
//   panel.y = {"Allan deviation [rad/s]", plot::Scale::kLog};
//   plot::Series& adev = panel.series.emplace_back();
//   adev.label = "gyro x";
//   adev.x = tau_s;  adev.y = sigma;  adev.y_low = lower;  adev.y_high = upper;
//   adev.marker = plot::Marker::kCircle;
//   const std::string svg = plot::RenderSvg(figure);
#ifndef SPLINECAL_PLOT_SVG_PLOT_H_
#define SPLINECAL_PLOT_SVG_PLOT_H_

#include <deque>
#include <limits>
#include <string>
#include <vector>

namespace splinecal {
namespace plot {

enum class Scale { kLinear, kLog };
enum class Marker { kNone, kCircle, kSquare };
enum class LegendPosition { kNone, kTopRight, kTopLeft, kBottomRight, kBottomLeft };

// One data series. x and y have the same length (RenderSvg CHECKs it).
struct Series {
  std::string label;  // legend text; empty keeps the series out of the legend
  std::vector<double> x;
  std::vector<double> y;
  // Optional error bars: the lower and upper y bound of every point (absolute values, not
  // offsets), both empty or both the size of y. A bound that is not finite (or <= 0 on a log
  // axis) is clamped to the edge of the plot.
  std::vector<double> y_low;
  std::vector<double> y_high;
  std::string color;  // "#rrggbb"; empty takes the next colour of the default palette
  bool line = true;   // connect consecutive points
  bool dashed = false;
  double line_width = 1.5;  // [px]
  Marker marker = Marker::kNone;
  double marker_size = 2.5;  // radius or half side [px]
};

struct Axis {
  std::string label;  // with its unit, e.g. "averaging time tau [s]"
  Scale scale = Scale::kLinear;
  // The range; NaN takes it from the data (log axes: whole decades; linear: round ticks).
  double min = std::numeric_limits<double>::quiet_NaN();
  double max = std::numeric_limits<double>::quiet_NaN();
  // Values grow towards the bottom (y) or the left (x) instead: image rows (v down) drawn the way
  // the image shows them.
  bool reversed = false;
};

struct Panel {
  std::string title;
  Axis x;
  Axis y;
  // Same data units per pixel on both axes, for top views of trajectories (linear axes only; the
  // range of one axis is widened about its centre).
  bool equal_aspect = false;
  bool grid = true;  // light grid lines at the major ticks
  LegendPosition legend = LegendPosition::kTopRight;
  // A deque, so that a reference from series.emplace_back() stays valid while more series are
  // added (plots are built that way; a vector reallocates under such references).
  std::deque<Series> series;
};

struct Figure {
  std::string title;  // above all panels; empty for none
  // Panels fill rows of `columns` panels, left to right, top to bottom (a 2x3 grid: 6 panels and
  // columns = 3; stacked time series: columns = 1).
  int columns = 1;
  double panel_width = 440.0;   // [px], including room for tick labels and axis labels
  double panel_height = 330.0;  // [px]
  std::deque<Panel> panels;     // a deque for the same reason as Panel::series
  // Prefix of the ids the document defines (one clip path per panel: "<id_prefix>-area-<panel>").
  // Ids are global to an HTML page, so SVGs inlined in one page need distinct prefixes, or a
  // panel is clipped by another figure's rectangle (HtmlPage::FigureSection gives each its own).
  // A letter, then letters, digits, '-' or '_' (RenderSvg CHECKs it).
  std::string id_prefix = "plot";
};

// Appends a panel titled `title` (may be empty) with linear axes labelled x_label and y_label and
// returns it (the reference stays valid while more panels are added).
Panel& AddPanel(Figure* figure,
                const std::string& title,
                const std::string& x_label,
                const std::string& y_label);

// `text` made safe for XML and HTML text and attribute values: & < > " ' become entities and
// control characters (which XML 1.0 forbids) become spaces.
std::string EscapeXml(const std::string& text);

// The SVG document of `figure`. CHECK-fails on programmer errors only (mismatched series sizes,
// columns < 1, non-positive panel size, a log axis with a given range <= 0, an id_prefix that is
// not an XML name).
std::string RenderSvg(const Figure& figure);

// A tick of an axis. Log-axis labels read "10^k" (drawn with a superscript exponent).
struct Tick {
  double value = 0.0;
  std::string label;  // empty for unlabelled minor ticks
  bool major = true;
};

// The ticks RenderSvg draws for an axis over [lo, hi] (lo < hi; lo > 0 on a log axis), in
// increasing order. Linear: a step of 1, 2 or 5 x 10^k giving 4 to 10 ticks, labels with just
// enough decimals. Log: every decade 10^k in range is a major tick (labels thinned to every 2nd,
// 3rd... decade when more than 8 decades are shown); minor ticks at 2..9 x 10^k when at most 6
// decades are shown.
std::vector<Tick> AxisTicks(double lo, double hi, Scale scale);

// The range RenderSvg uses for data spanning [lo, hi] (finite, lo <= hi, lo > 0 on a log axis):
// log axes widen to whole decades; linear axes widen to multiples of the tick step. A single
// value gets a range around it.
void AutoRange(double lo, double hi, Scale scale, double* range_lo, double* range_hi);

}  // namespace plot
}  // namespace splinecal

#endif  // SPLINECAL_PLOT_SVG_PLOT_H_
