#include "splinecal/plot/svg_plot.h"

#include <glog/logging.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/string_printf.h"

namespace splinecal {
namespace plot {
namespace {

// Layout of one panel [px]: room left for the y tick labels and the rotated y label, below for
// the x tick labels and the x label, above for the panel title.
constexpr double kMarginLeft = 80.0;
constexpr double kMarginRight = 18.0;
constexpr double kMarginTop = 28.0;
constexpr double kMarginBottom = 46.0;
constexpr double kFigureTitleHeight = 30.0;
constexpr double kMajorTickLength = 6.0;
constexpr double kMinorTickLength = 3.0;
constexpr double kFontSize = 12.0;
constexpr double kTickFontSize = 11.0;
constexpr double kLegendFontSize = 11.0;
// Average advance of a character of the sans-serif font at kLegendFontSize, for sizing the legend
// box (an estimate; SVG has no text metrics).
constexpr double kLegendCharWidth = 6.2;
constexpr double kLegendRowHeight = 16.0;
// Normalised coordinates (0..1 across the plot area) are clamped to +-kFarAway before they become
// pixels, so that a value like 1e300 on an axis of range 1 cannot overflow. Anything beyond is
// off the plot by a billion plot widths; only the direction of such a segment changes.
constexpr double kFarAway = 1e9;
// Tolerance [decades or steps] for deciding that a value sits on a tick, absorbing the rounding
// of log10 and of step multiples.
constexpr double kTickSlack = 1e-9;

// Default colours (a common ten-colour qualitative palette), in order of use.
const char* const kPalette[] = {"#1f77b4",
                                "#d62728",
                                "#2ca02c",
                                "#ff7f0e",
                                "#9467bd",
                                "#8c564b",
                                "#e377c2",
                                "#7f7f7f",
                                "#bcbd22",
                                "#17becf"};
constexpr int kPaletteSize = sizeof(kPalette) / sizeof(kPalette[0]);

// A pixel coordinate with two decimals; "-0.00" printed as "0.00" so output does not depend on
// the sign of a zero.
std::string Px(double value) {
  const std::string text = StringPrintf("%.2f", value);
  return text == "-0.00" ? "0.00" : text;
}

// Number of characters (UTF-8 code points), for estimating text width.
int CharCount(const std::string& text) {
  int count = 0;
  for (char c : text) {
    if ((static_cast<unsigned char>(c) & 0xc0) != 0x80) ++count;
  }
  return count;
}

// Tick label markup: "10^k" becomes 10 with a superscript k.
std::string TickLabelMarkup(const std::string& label) {
  const size_t caret = label.find('^');
  if (caret == std::string::npos) return EscapeXml(label);
  return EscapeXml(label.substr(0, caret)) + "<tspan dy=\"-5\" font-size=\"8\">" +
         EscapeXml(label.substr(caret + 1)) + "</tspan>";
}

// A letter, then letters, digits, '-' or '_': safe as an XML id and in url(#...) unescaped.
bool IsXmlName(const std::string& text) {
  if (text.empty() || !std::isalpha(static_cast<unsigned char>(text[0]))) return false;
  for (char c : text) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '-' && c != '_') return false;
  }
  return true;
}

double Pow10(int exponent) { return std::pow(10.0, exponent); }

// The linear tick step: 1, 2 or 5 x 10^k, about a fifth of the range.
double NiceStep(double range) {
  const double raw = range / 5.0;
  const double magnitude = Pow10(static_cast<int>(std::floor(std::log10(raw))));
  const double normalised = raw / magnitude;
  double nice = 10.0;
  if (normalised < 1.5) {
    nice = 1.0;
  } else if (normalised < 3.0) {
    nice = 2.0;
  } else if (normalised < 7.0) {
    nice = 5.0;
  }
  return nice * magnitude;
}

std::string LinearLabel(double value, double step, double largest) {
  if (std::abs(value) < step * 1e-6) value = 0.0;
  const int step_exponent = static_cast<int>(std::floor(std::log10(step) + kTickSlack));
  if (largest >= 1e6 || step < 1e-4) {
    const int largest_exponent =
        static_cast<int>(std::floor(std::log10(std::max(largest, step)) + kTickSlack));
    const int digits = std::clamp(largest_exponent - step_exponent + 1, 1, 17);
    return StringPrintf("%.*g", digits, value);
  }
  const int decimals = std::max(0, -step_exponent);
  return StringPrintf("%.*f", decimals, value);
}

std::string DecadeLabel(int exponent) { return "10^" + std::to_string(exponent); }

// Maps data values of one axis to pixels.
class AxisMap {
 public:
  AxisMap(Scale scale, double lo, double hi, double pixel_lo, double pixel_hi)
      : scale_(scale), pixel_lo_(pixel_lo), pixel_hi_(pixel_hi) {
    lo_ = Transform(lo);
    hi_ = Transform(hi);
  }
  // Values that cannot be placed on this axis (non-finite; <= 0 on a log axis).
  bool Valid(double value) const {
    return std::isfinite(value) && (scale_ == Scale::kLinear || value > 0.0);
  }
  // Position across the axis, 0 at lo and 1 at hi (clamped to +-kFarAway).
  double Fraction(double value) const {
    const double fraction = (Transform(value) - lo_) / (hi_ - lo_);
    return std::clamp(fraction, -kFarAway, kFarAway);
  }
  double Pixel(double value) const { return pixel_lo_ + Fraction(value) * (pixel_hi_ - pixel_lo_); }

 private:
  double Transform(double value) const { return scale_ == Scale::kLog ? std::log10(value) : value; }

  Scale scale_;
  double lo_ = 0.0;
  double hi_ = 1.0;
  double pixel_lo_;
  double pixel_hi_;
};

struct Rect {
  double left, top, right, bottom;
};

// Liang-Barsky clipping of the segment (x0, y0)-(x1, y1) to `r`. Returns false when nothing is
// visible; otherwise the clipped end points and whether each end was moved.
bool ClipSegment(const Rect& r,
                 double* x0,
                 double* y0,
                 double* x1,
                 double* y1,
                 bool* start_clipped,
                 bool* end_clipped) {
  const double dx = *x1 - *x0;
  const double dy = *y1 - *y0;
  double t0 = 0.0;
  double t1 = 1.0;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {*x0 - r.left, r.right - *x0, *y0 - r.top, r.bottom - *y0};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
      continue;
    }
    const double t = q[i] / p[i];
    if (p[i] < 0.0) {
      if (t > t1) return false;
      t0 = std::max(t0, t);
    } else {
      if (t < t0) return false;
      t1 = std::min(t1, t);
    }
  }
  *start_clipped = t0 > 0.0;
  *end_clipped = t1 < 1.0;
  const double sx = *x0;
  const double sy = *y0;
  *x0 = sx + t0 * dx;
  *y0 = sy + t0 * dy;
  *x1 = sx + t1 * dx;
  *y1 = sy + t1 * dy;
  return true;
}

// The data extent of an axis: finite values (> 0 on a log axis).
struct Extent {
  double lo = std::numeric_limits<double>::infinity();
  double hi = -std::numeric_limits<double>::infinity();
  void Add(double value, Scale scale) {
    if (!std::isfinite(value) || (scale == Scale::kLog && value <= 0.0)) return;
    lo = std::min(lo, value);
    hi = std::max(hi, value);
  }
  bool empty() const { return lo > hi; }
};

bool PointValid(const Panel& panel, double x, double y) {
  const bool x_ok = std::isfinite(x) && (panel.x.scale == Scale::kLinear || x > 0.0);
  const bool y_ok = std::isfinite(y) && (panel.y.scale == Scale::kLinear || y > 0.0);
  return x_ok && y_ok;
}

void ResolveRange(const Axis& axis, const Extent& extent, double* lo, double* hi) {
  const bool have_min = std::isfinite(axis.min);
  const bool have_max = std::isfinite(axis.max);
  if (have_min && have_max) {
    CHECK_LT(axis.min, axis.max) << "axis '" << axis.label << "': min must be below max";
    if (axis.scale == Scale::kLog) CHECK_GT(axis.min, 0.0) << "log axis '" << axis.label << "'";
    *lo = axis.min;
    *hi = axis.max;
    return;
  }
  double data_lo = extent.lo;
  double data_hi = extent.hi;
  if (extent.empty()) {
    data_lo = axis.scale == Scale::kLog ? 1.0 : 0.0;
    data_hi = axis.scale == Scale::kLog ? 10.0 : 1.0;
  }
  if (have_min) data_lo = axis.min;
  if (have_max) data_hi = axis.max;
  if (data_lo > data_hi) std::swap(data_lo, data_hi);
  AutoRange(data_lo, data_hi, axis.scale, lo, hi);
  if (have_min) *lo = axis.min;
  if (have_max) *hi = axis.max;
  if (!(*lo < *hi)) {
    // A one-sided range that excludes all data: fall back to a unit range from the given end.
    if (axis.scale == Scale::kLog) {
      if (have_min)
        *hi = *lo * 10.0;
      else
        *lo = *hi / 10.0;
    } else {
      if (have_min)
        *hi = *lo + 1.0;
      else
        *lo = *hi - 1.0;
    }
  }
}

// Widens one of the linear ranges so that a data unit has the same length in x and y.
void EqualAspect(
    double width, double height, double* x_lo, double* x_hi, double* y_lo, double* y_hi) {
  const double x_per_px = (*x_hi - *x_lo) / width;
  const double y_per_px = (*y_hi - *y_lo) / height;
  if (x_per_px < y_per_px) {
    const double half = 0.5 * y_per_px * width;
    const double centre = 0.5 * (*x_lo + *x_hi);
    *x_lo = centre - half;
    *x_hi = centre + half;
  } else {
    const double half = 0.5 * x_per_px * height;
    const double centre = 0.5 * (*y_lo + *y_hi);
    *y_lo = centre - half;
    *y_hi = centre + half;
  }
}

class PanelWriter {
 public:
  PanelWriter(const Panel& panel,
              const std::string& clip_id,
              double panel_width,
              double panel_height,
              std::string* out)
      : panel_(panel), clip_id_(clip_id), out_(out) {
    area_ = {kMarginLeft, kMarginTop, panel_width - kMarginRight, panel_height - kMarginBottom};
    CHECK_GT(area_.right, area_.left) << "panel_width too small";
    CHECK_GT(area_.bottom, area_.top) << "panel_height too small";
  }

  void Write() {
    Extent x_extent;
    Extent y_extent;
    for (const Series& series : panel_.series) {
      CHECK_EQ(series.x.size(), series.y.size()) << "series '" << series.label << "': x and y";
      CHECK_EQ(series.y_low.size(), series.y_high.size())
          << "series '" << series.label << "': y_low and y_high";
      CHECK(series.y_low.empty() || series.y_low.size() == series.y.size())
          << "series '" << series.label << "': error bars need one bound per point";
      for (size_t i = 0; i < series.x.size(); ++i) {
        if (!PointValid(panel_, series.x[i], series.y[i])) continue;
        x_extent.Add(series.x[i], panel_.x.scale);
        y_extent.Add(series.y[i], panel_.y.scale);
        if (!series.y_low.empty()) {
          y_extent.Add(series.y_low[i], panel_.y.scale);
          y_extent.Add(series.y_high[i], panel_.y.scale);
        }
      }
    }
    ResolveRange(panel_.x, x_extent, &x_lo_, &x_hi_);
    ResolveRange(panel_.y, y_extent, &y_lo_, &y_hi_);
    if (panel_.equal_aspect && panel_.x.scale == Scale::kLinear &&
        panel_.y.scale == Scale::kLinear) {
      EqualAspect(
          area_.right - area_.left, area_.bottom - area_.top, &x_lo_, &x_hi_, &y_lo_, &y_hi_);
    }
    const AxisMap x_map(panel_.x.scale,
                        x_lo_,
                        x_hi_,
                        panel_.x.reversed ? area_.right : area_.left,
                        panel_.x.reversed ? area_.left : area_.right);
    const AxisMap y_map(panel_.y.scale,
                        y_lo_,
                        y_hi_,
                        panel_.y.reversed ? area_.top : area_.bottom,
                        panel_.y.reversed ? area_.bottom : area_.top);

    const double centre_x = 0.5 * (area_.left + area_.right);
    if (!panel_.title.empty()) {
      *out_ += "<text x=\"" + Px(centre_x) + "\" y=\"18\" text-anchor=\"middle\" " +
               "font-weight=\"bold\">" + EscapeXml(panel_.title) + "</text>\n";
    }
    *out_ += "<defs><clipPath id=\"" + clip_id_ + "\"><rect " + RectAttributes() +
             "/></clipPath></defs>\n";
    *out_ += "<rect " + RectAttributes() + " fill=\"white\" stroke=\"none\"/>\n";

    const std::vector<Tick> x_ticks = AxisTicks(x_lo_, x_hi_, panel_.x.scale);
    const std::vector<Tick> y_ticks = AxisTicks(y_lo_, y_hi_, panel_.y.scale);
    WriteGrid(x_ticks, y_ticks, x_map, y_map);
    *out_ += "<rect " + RectAttributes() + " fill=\"none\" stroke=\"black\"/>\n";
    WriteTicks(x_ticks, y_ticks, x_map, y_map);

    if (!panel_.x.label.empty()) {
      *out_ += "<text x=\"" + Px(centre_x) + "\" y=\"" + Px(area_.bottom + 38) +
               "\" text-anchor=\"middle\">" + EscapeXml(panel_.x.label) + "</text>\n";
    }
    if (!panel_.y.label.empty()) {
      const double centre_y = 0.5 * (area_.top + area_.bottom);
      *out_ += "<text transform=\"translate(16," + Px(centre_y) +
               ") rotate(-90)\" text-anchor=\"middle\">" + EscapeXml(panel_.y.label) + "</text>\n";
    }

    *out_ += "<g clip-path=\"url(#" + clip_id_ + ")\">\n";
    for (size_t s = 0; s < panel_.series.size(); ++s) {
      WriteSeries(panel_.series[s], ColorOf(s), x_map, y_map);
    }
    *out_ += "</g>\n";
    WriteLegend();
  }

 private:
  std::string RectAttributes() const {
    return "x=\"" + Px(area_.left) + "\" y=\"" + Px(area_.top) + "\" width=\"" +
           Px(area_.right - area_.left) + "\" height=\"" + Px(area_.bottom - area_.top) + "\"";
  }

  std::string ColorOf(size_t series_index) const {
    // Series without a colour take the palette in order, counting only those series.
    int automatic = 0;
    for (size_t s = 0; s < series_index; ++s) {
      if (panel_.series[s].color.empty()) ++automatic;
    }
    const Series& series = panel_.series[series_index];
    return series.color.empty() ? kPalette[automatic % kPaletteSize] : EscapeXml(series.color);
  }

  void WriteGrid(const std::vector<Tick>& x_ticks,
                 const std::vector<Tick>& y_ticks,
                 const AxisMap& x_map,
                 const AxisMap& y_map) {
    if (!panel_.grid) return;
    std::string path;
    for (const Tick& tick : x_ticks) {
      if (!tick.major) continue;
      path += "M" + Px(x_map.Pixel(tick.value)) + " " + Px(area_.top) + "V" + Px(area_.bottom);
    }
    for (const Tick& tick : y_ticks) {
      if (!tick.major) continue;
      path += "M" + Px(area_.left) + " " + Px(y_map.Pixel(tick.value)) + "H" + Px(area_.right);
    }
    if (!path.empty()) {
      *out_ += "<path d=\"" + path + "\" stroke=\"#e3e3e3\" stroke-width=\"1\" fill=\"none\"/>\n";
    }
  }

  void WriteTicks(const std::vector<Tick>& x_ticks,
                  const std::vector<Tick>& y_ticks,
                  const AxisMap& x_map,
                  const AxisMap& y_map) {
    std::string path;
    std::string labels;
    for (const Tick& tick : x_ticks) {
      const double x = x_map.Pixel(tick.value);
      const double length = tick.major ? kMajorTickLength : kMinorTickLength;
      path += "M" + Px(x) + " " + Px(area_.bottom) + "v" + Px(length);
      if (!tick.label.empty()) {
        labels += "<text x=\"" + Px(x) + "\" y=\"" + Px(area_.bottom + 20) +
                  "\" text-anchor=\"middle\">" + TickLabelMarkup(tick.label) + "</text>\n";
      }
    }
    for (const Tick& tick : y_ticks) {
      const double y = y_map.Pixel(tick.value);
      const double length = tick.major ? kMajorTickLength : kMinorTickLength;
      path += "M" + Px(area_.left) + " " + Px(y) + "h" + Px(-length);
      if (!tick.label.empty()) {
        labels += "<text x=\"" + Px(area_.left - 9) + "\" y=\"" + Px(y + 4) +
                  "\" text-anchor=\"end\">" + TickLabelMarkup(tick.label) + "</text>\n";
      }
    }
    if (!path.empty()) {
      *out_ += "<path d=\"" + path + "\" stroke=\"black\" stroke-width=\"1\" fill=\"none\"/>\n";
    }
    if (!labels.empty()) {
      *out_ += "<g font-size=\"" + Px(kTickFontSize) + "\">\n" + labels + "</g>\n";
    }
  }

  void WriteSeries(const Series& series,
                   const std::string& color,
                   const AxisMap& x_map,
                   const AxisMap& y_map) {
    const std::string stroke = "stroke=\"" + color + "\"";
    const size_t n = series.x.size();
    // Error bars: vertical bars with short caps, clipped to the plot area.
    if (!series.y_low.empty()) {
      std::string path;
      for (size_t i = 0; i < n; ++i) {
        if (!PointValid(panel_, series.x[i], series.y[i])) continue;
        const double x = x_map.Pixel(series.x[i]);
        if (x < area_.left - 1.0 || x > area_.right + 1.0) continue;
        // A bound that cannot be placed goes to its end of the axis (the bottom unless reversed).
        const double low = y_map.Pixel(y_map.Valid(series.y_low[i]) ? series.y_low[i] : y_lo_);
        const double high = y_map.Pixel(y_map.Valid(series.y_high[i]) ? series.y_high[i] : y_hi_);
        const double y0 = std::clamp(std::max(low, high), area_.top, area_.bottom);
        const double y1 = std::clamp(std::min(low, high), area_.top, area_.bottom);
        path += "M" + Px(x) + " " + Px(y0) + "V" + Px(y1);
        path += "M" + Px(x - 2.5) + " " + Px(y0) + "h5";
        path += "M" + Px(x - 2.5) + " " + Px(y1) + "h5";
      }
      if (!path.empty()) {
        *out_ += "<path d=\"" + path + "\" " + stroke + " stroke-width=\"1\" fill=\"none\"/>\n";
      }
    }
    if (series.line) {
      // Runs of consecutive valid points, each segment clipped to the plot area; a segment that
      // starts where the previous one ended continues the same polyline.
      const Rect bounds = area_;
      std::string points;
      bool open = false;
      auto close = [&]() {
        if (open) {
          *out_ += "<polyline points=\"" + points + "\" fill=\"none\" " + stroke +
                   " stroke-width=\"" + Px(series.line_width) + "\"" +
                   (series.dashed ? " stroke-dasharray=\"6,4\"" : "") +
                   " stroke-linejoin=\"round\"/>\n";
        }
        points.clear();
        open = false;
      };
      for (size_t i = 0; i + 1 < n; ++i) {
        if (!PointValid(panel_, series.x[i], series.y[i]) ||
            !PointValid(panel_, series.x[i + 1], series.y[i + 1])) {
          close();
          continue;
        }
        double x0 = x_map.Pixel(series.x[i]);
        double y0 = y_map.Pixel(series.y[i]);
        double x1 = x_map.Pixel(series.x[i + 1]);
        double y1 = y_map.Pixel(series.y[i + 1]);
        bool start_clipped = false;
        bool end_clipped = false;
        if (!ClipSegment(bounds, &x0, &y0, &x1, &y1, &start_clipped, &end_clipped)) {
          close();
          continue;
        }
        if (start_clipped) close();
        if (!open) {
          points = Px(x0) + "," + Px(y0);
          open = true;
        }
        points += " " + Px(x1) + "," + Px(y1);
        if (end_clipped) close();
      }
      close();
    }
    if (series.marker != Marker::kNone) {
      std::string path;
      const double r = series.marker_size;
      for (size_t i = 0; i < n; ++i) {
        if (!PointValid(panel_, series.x[i], series.y[i])) continue;
        const double x = x_map.Pixel(series.x[i]);
        const double y = y_map.Pixel(series.y[i]);
        if (x < area_.left - r || x > area_.right + r || y < area_.top - r ||
            y > area_.bottom + r) {
          continue;
        }
        path += MarkerPath(series.marker, x, y, r);
      }
      if (!path.empty()) {
        *out_ += "<path d=\"" + path + "\" fill=\"" + color + "\" stroke=\"none\"/>\n";
      }
    }
  }

  static std::string MarkerPath(Marker marker, double x, double y, double r) {
    if (marker == Marker::kSquare) {
      return "M" + Px(x - r) + " " + Px(y - r) + "h" + Px(2 * r) + "v" + Px(2 * r) + "h" +
             Px(-2 * r) + "z";
    }
    // A circle as two half arcs.
    return "M" + Px(x - r) + " " + Px(y) + "a" + Px(r) + " " + Px(r) + " 0 1 0 " + Px(2 * r) +
           " 0a" + Px(r) + " " + Px(r) + " 0 1 0 " + Px(-2 * r) + " 0z";
  }

  void WriteLegend() {
    if (panel_.legend == LegendPosition::kNone) return;
    std::vector<size_t> entries;
    int widest = 0;
    for (size_t s = 0; s < panel_.series.size(); ++s) {
      if (panel_.series[s].label.empty()) continue;
      entries.push_back(s);
      widest = std::max(widest, CharCount(panel_.series[s].label));
    }
    if (entries.empty()) return;
    constexpr double kPad = 6.0;
    constexpr double kSampleWidth = 22.0;
    const double width = kPad + kSampleWidth + kPad + widest * kLegendCharWidth + kPad;
    const double height = kPad + entries.size() * kLegendRowHeight + kPad - 4.0;
    const bool left =
        panel_.legend == LegendPosition::kTopLeft || panel_.legend == LegendPosition::kBottomLeft;
    const bool top =
        panel_.legend == LegendPosition::kTopLeft || panel_.legend == LegendPosition::kTopRight;
    const double x = left ? area_.left + 8.0 : area_.right - 8.0 - width;
    const double y = top ? area_.top + 8.0 : area_.bottom - 8.0 - height;
    *out_ += "<g font-size=\"" + Px(kLegendFontSize) + "\">\n";
    *out_ += "<rect x=\"" + Px(x) + "\" y=\"" + Px(y) + "\" width=\"" + Px(width) + "\" height=\"" +
             Px(height) + "\" fill=\"white\" fill-opacity=\"0.85\" stroke=\"#999999\"/>\n";
    for (size_t e = 0; e < entries.size(); ++e) {
      const Series& series = panel_.series[entries[e]];
      const std::string color = ColorOf(entries[e]);
      const double row_y = y + kPad + (e + 0.5) * kLegendRowHeight - 2.0;
      const double sample_x = x + kPad;
      if (series.line) {
        *out_ += "<path d=\"M" + Px(sample_x) + " " + Px(row_y) + "h" + Px(kSampleWidth) +
                 "\" stroke=\"" + color + "\" stroke-width=\"" + Px(series.line_width) + "\"" +
                 (series.dashed ? " stroke-dasharray=\"6,4\"" : "") + " fill=\"none\"/>\n";
      } else if (!series.y_low.empty()) {
        *out_ += "<path d=\"M" + Px(sample_x + kSampleWidth / 2) + " " + Px(row_y - 5) + "v10" +
                 "\" stroke=\"" + color + "\" stroke-width=\"1\" fill=\"none\"/>\n";
      }
      if (series.marker != Marker::kNone) {
        *out_ += "<path d=\"" +
                 MarkerPath(series.marker, sample_x + kSampleWidth / 2, row_y, series.marker_size) +
                 "\" fill=\"" + color + "\" stroke=\"none\"/>\n";
      }
      *out_ += "<text x=\"" + Px(sample_x + kSampleWidth + kPad) + "\" y=\"" + Px(row_y + 4) +
               "\">" + EscapeXml(series.label) + "</text>\n";
    }
    *out_ += "</g>\n";
  }

  const Panel& panel_;
  std::string clip_id_;
  std::string* out_;
  Rect area_;
  double x_lo_ = 0.0;
  double x_hi_ = 1.0;
  double y_lo_ = 0.0;
  double y_hi_ = 1.0;
};

}  // namespace

Panel& AddPanel(Figure* figure,
                const std::string& title,
                const std::string& x_label,
                const std::string& y_label) {
  Panel& panel = figure->panels.emplace_back();
  panel.title = title;
  panel.x.label = x_label;
  panel.y.label = y_label;
  return panel;
}

std::string EscapeXml(const std::string& text) {
  std::string escaped;
  escaped.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&':
        escaped += "&amp;";
        break;
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '"':
        escaped += "&quot;";
        break;
      case '\'':
        escaped += "&apos;";
        break;
      default:
        // Control characters are not allowed in XML 1.0 text.
        if (static_cast<unsigned char>(c) < 0x20 && c != '\t' && c != '\n') {
          escaped += ' ';
        } else {
          escaped += c;
        }
    }
  }
  return escaped;
}

void AutoRange(double lo, double hi, Scale scale, double* range_lo, double* range_hi) {
  CHECK(std::isfinite(lo) && std::isfinite(hi) && lo <= hi)
      << "AutoRange(" << lo << ", " << hi << ")";
  if (scale == Scale::kLog) {
    CHECK_GT(lo, 0.0) << "AutoRange on a log axis";
    int lo_decade = static_cast<int>(std::floor(std::log10(lo) + kTickSlack));
    int hi_decade = static_cast<int>(std::ceil(std::log10(hi) - kTickSlack));
    if (hi_decade <= lo_decade) hi_decade = lo_decade + 1;
    *range_lo = Pow10(lo_decade);
    *range_hi = Pow10(hi_decade);
    return;
  }
  if (lo == hi) {
    const double half = lo == 0.0 ? 1.0 : 0.1 * std::abs(lo);
    lo -= half;
    hi += half;
  }
  const double step = NiceStep(hi - lo);
  *range_lo = std::floor(lo / step + kTickSlack) * step;
  *range_hi = std::ceil(hi / step - kTickSlack) * step;
}

std::vector<Tick> AxisTicks(double lo, double hi, Scale scale) {
  CHECK(std::isfinite(lo) && std::isfinite(hi) && lo < hi)
      << "AxisTicks(" << lo << ", " << hi << ")";
  std::vector<Tick> ticks;
  if (scale == Scale::kLinear) {
    const double step = NiceStep(hi - lo);
    const double largest = std::max(std::abs(lo), std::abs(hi));
    const double first = std::ceil(lo / step - kTickSlack);
    const double last = std::floor(hi / step + kTickSlack);
    for (double k = first; k <= last; k += 1.0) {
      const double value = k * step;
      ticks.push_back({value, LinearLabel(value, step, largest), true});
    }
    return ticks;
  }
  CHECK_GT(lo, 0.0) << "AxisTicks on a log axis";
  const double log_lo = std::log10(lo);
  const double log_hi = std::log10(hi);
  const int first_decade = static_cast<int>(std::ceil(log_lo - kTickSlack));
  const int last_decade = static_cast<int>(std::floor(log_hi + kTickSlack));
  const int num_decades = last_decade - first_decade + 1;
  const int stride = num_decades > 8 ? (num_decades + 7) / 8 : 1;
  for (int k = first_decade; k <= last_decade; ++k) {
    const bool labelled = ((k % stride) + stride) % stride == 0;
    ticks.push_back({Pow10(k), labelled ? DecadeLabel(k) : std::string(), true});
  }
  if (log_hi - log_lo <= 6.0 + kTickSlack) {
    // Minor ticks 2..9 x 10^d; labelled when fewer than two decades are in range, so that every
    // axis has at least two labelled values.
    const bool label_minor = num_decades < 2;
    for (int d = static_cast<int>(std::floor(log_lo)) - 1; d <= last_decade; ++d) {
      for (int j = 2; j <= 9; ++j) {
        const double value = j * Pow10(d);
        const double log_value = std::log10(value);
        if (log_value < log_lo - kTickSlack || log_value > log_hi + kTickSlack) continue;
        ticks.push_back({value, label_minor ? StringPrintf("%g", value) : std::string(), false});
      }
    }
    std::sort(
        ticks.begin(), ticks.end(), [](const Tick& a, const Tick& b) { return a.value < b.value; });
  }
  return ticks;
}

std::string RenderSvg(const Figure& figure) {
  CHECK_GE(figure.columns, 1) << "Figure::columns";
  CHECK(figure.panel_width > 0.0 && figure.panel_height > 0.0) << "Figure panel size";
  CHECK(IsXmlName(figure.id_prefix)) << "Figure::id_prefix '" << figure.id_prefix << "'";
  const int num_panels = static_cast<int>(figure.panels.size());
  const int columns = std::min(figure.columns, std::max(num_panels, 1));
  const int rows = (num_panels + columns - 1) / columns;
  const double title_height = figure.title.empty() ? 0.0 : kFigureTitleHeight;
  const double width = columns * figure.panel_width;
  const double height = std::max(1.0, title_height + rows * figure.panel_height);

  std::string out;
  out += "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out += "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\" width=\"" + Px(width) +
         "\" height=\"" + Px(height) + "\" viewBox=\"0 0 " + Px(width) + " " + Px(height) +
         "\" font-family=\"Helvetica, Arial, sans-serif\" font-size=\"" + Px(kFontSize) + "\">\n";
  out += "<rect x=\"0\" y=\"0\" width=\"" + Px(width) + "\" height=\"" + Px(height) +
         "\" fill=\"white\"/>\n";
  if (!figure.title.empty()) {
    out += "<text x=\"" + Px(width / 2) + "\" y=\"21\" text-anchor=\"middle\" font-size=\"15\" " +
           "font-weight=\"bold\">" + EscapeXml(figure.title) + "</text>\n";
  }
  for (int p = 0; p < num_panels; ++p) {
    const double x = (p % columns) * figure.panel_width;
    const double y = title_height + (p / columns) * figure.panel_height;
    out += "<g transform=\"translate(" + Px(x) + "," + Px(y) + ")\">\n";
    const std::string clip_id = figure.id_prefix + "-area-" + std::to_string(p);
    PanelWriter(figure.panels[p], clip_id, figure.panel_width, figure.panel_height, &out).Write();
    out += "</g>\n";
  }
  out += "</svg>\n";
  return out;
}

}  // namespace plot
}  // namespace splinecal
