#include "splinecal/plot/svg_plot.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <regex>
#include <string>
#include <vector>

#include "testing/text_checks.h"

namespace splinecal {
namespace plot {
namespace {

using ::testing::HasSubstr;
using ::testing::Not;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();
// Tick values are computed as k * step or 10^k: exact to a few ulps.
constexpr double kTickTolerance = 1e-12;

// A small XML well-formedness check: one root element, every tag closed in order, attribute values
// quoted, '&' only in entities, no '<' in text. Returns "" or the first problem.
std::string XmlProblem(const std::string& xml) {
  std::vector<std::string> open;
  size_t i = 0;
  int roots = 0;
  if (xml.rfind("<?xml", 0) != 0) return "no XML declaration";
  i = xml.find("?>") + 2;
  while (i < xml.size()) {
    if (xml[i] == '&') {
      const size_t semicolon = xml.find(';', i);
      if (semicolon == std::string::npos) return "bare &";
      const std::string entity = xml.substr(i, semicolon - i + 1);
      if (entity != "&amp;" && entity != "&lt;" && entity != "&gt;" && entity != "&quot;" &&
          entity != "&apos;") {
        return "unknown entity " + entity;
      }
      i = semicolon + 1;
      continue;
    }
    if (xml[i] != '<') {
      ++i;
      continue;
    }
    // A tag: find its end, skipping quoted attribute values.
    size_t j = i + 1;
    char quote = 0;
    while (j < xml.size() && (quote != 0 || xml[j] != '>')) {
      if (quote == 0 && (xml[j] == '"' || xml[j] == '\'')) {
        quote = xml[j];
      } else if (quote != 0 && xml[j] == quote) {
        quote = 0;
      } else if (quote != 0 && xml[j] == '<') {
        return "'<' inside an attribute";
      }
      ++j;
    }
    if (j >= xml.size()) return "unterminated tag";
    const std::string tag = xml.substr(i + 1, j - i - 1);
    if (tag.empty()) return "empty tag";
    if (tag[0] == '/') {
      const std::string name = tag.substr(1);
      if (open.empty() || open.back() != name) return "unexpected </" + name + ">";
      open.pop_back();
    } else {
      const std::string name = tag.substr(0, tag.find_first_of(" \t\n/"));
      if (tag.back() != '/') {
        if (open.empty()) ++roots;
        open.push_back(name);
      } else if (open.empty()) {
        ++roots;
      }
    }
    i = j + 1;
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  if (roots != 1) return "expected one root element, found " + std::to_string(roots);
  return "";
}

int Count(const std::string& text, const std::string& what) {
  int count = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++count;
  return count;
}

// The largest absolute value of any number written in the document.
double LargestNumber(const std::string& text) {
  const std::regex number(R"(-?[0-9]+(\.[0-9]+)?(e[-+]?[0-9]+)?)");
  double largest = 0.0;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), number);
       it != std::sregex_iterator();
       ++it) {
    largest = std::max(largest, std::abs(std::stod(it->str())));
  }
  return largest;
}

Figure AllanLikeFigure() {
  Figure figure;
  figure.title = "Allan deviation";
  Panel& panel = figure.panels.emplace_back();
  panel.title = "gyro x";
  panel.x = {"averaging time tau [s]", Scale::kLog};
  panel.y = {"Allan deviation [rad/s]", Scale::kLog};
  Series& adev = panel.series.emplace_back();
  adev.label = "measured";
  adev.marker = Marker::kCircle;
  for (int i = 0; i < 30; ++i) {
    const double tau = 0.005 * std::pow(10.0, i / 6.0);
    adev.x.push_back(tau);
    adev.y.push_back(1.7e-4 / std::sqrt(tau) + 1.9e-5 * std::sqrt(tau / 3.0));
    adev.y_low.push_back(adev.y.back() * 0.9);
    adev.y_high.push_back(adev.y.back() * 1.1);
  }
  Series& line = panel.series.emplace_back();
  line.label = "white noise N = 1.7e-4 rad/s/√Hz";
  line.dashed = true;
  line.x = {0.005, 100.0};
  line.y = {1.7e-4 / std::sqrt(0.005), 1.7e-4 / std::sqrt(100.0)};
  return figure;
}

TEST(AxisTicks, LogAxisHasMajorTicksAtEveryDecade) {
  const std::vector<Tick> ticks = AxisTicks(1e-3, 1e2, Scale::kLog);
  std::vector<double> majors;
  std::vector<std::string> labels;
  int minors = 0;
  for (const Tick& tick : ticks) {
    if (tick.major) {
      majors.push_back(tick.value);
      labels.push_back(tick.label);
    } else {
      ++minors;
      EXPECT_TRUE(tick.label.empty());
    }
  }
  ASSERT_EQ(majors.size(), 6u);
  for (int k = -3; k <= 2; ++k) {
    EXPECT_NEAR(majors[k + 3], std::pow(10.0, k), kTickTolerance * std::pow(10.0, k));
    EXPECT_EQ(labels[k + 3], "10^" + std::to_string(k));
  }
  EXPECT_EQ(minors, 5 * 8);  // 2..9 in each of the 5 decades
  for (size_t i = 1; i < ticks.size(); ++i) EXPECT_LT(ticks[i - 1].value, ticks[i].value);
}

TEST(AxisTicks, ManyDecadesThinLabelsAndDropMinorTicks) {
  const std::vector<Tick> ticks = AxisTicks(1e-10, 1e10, Scale::kLog);
  ASSERT_EQ(ticks.size(), 21u);
  int labelled = 0;
  for (const Tick& tick : ticks) {
    EXPECT_TRUE(tick.major);
    if (!tick.label.empty()) ++labelled;
  }
  EXPECT_EQ(labelled, 7);  // every 3rd decade: -9, -6, ..., 9
  EXPECT_EQ(ticks[1].label, "10^-9");
  EXPECT_EQ(ticks[10].label, "10^0");
  EXPECT_EQ(ticks[11].label, "");
}

TEST(AxisTicks, LogRangeWithinOneDecadeLabelsMinorTicks) {
  const std::vector<Tick> ticks = AxisTicks(2.0, 8.0, Scale::kLog);
  ASSERT_EQ(ticks.size(), 7u);
  EXPECT_EQ(ticks.front().label, "2");
  EXPECT_EQ(ticks.back().label, "8");
}

TEST(AxisTicks, LinearAxisUsesRoundSteps) {
  std::vector<Tick> ticks = AxisTicks(0.0, 10.0, Scale::kLinear);
  ASSERT_EQ(ticks.size(), 6u);
  for (int i = 0; i < 6; ++i) {
    EXPECT_NEAR(ticks[i].value, 2.0 * i, kTickTolerance);
    EXPECT_EQ(ticks[i].label, std::to_string(2 * i));
  }
  ticks = AxisTicks(-1.0, 1.0, Scale::kLinear);
  ASSERT_EQ(ticks.size(), 5u);
  EXPECT_EQ(ticks[0].label, "-1.0");
  EXPECT_EQ(ticks[2].label, "0.0");  // never "-0.0"
  ticks = AxisTicks(0.0, 0.0012, Scale::kLinear);
  EXPECT_EQ(ticks[1].label, "0.0002");
  ticks = AxisTicks(1.0e9, 2.0e9, Scale::kLinear);
  EXPECT_EQ(ticks[0].label, "1e+09");
  EXPECT_EQ(ticks[1].label, "1.2e+09");
}

TEST(AutoRange, LogWidensToDecadesLinearToSteps) {
  double lo = 0.0;
  double hi = 0.0;
  AutoRange(3e-4, 20.0, Scale::kLog, &lo, &hi);
  EXPECT_NEAR(lo, 1e-4, 1e-4 * kTickTolerance);
  EXPECT_NEAR(hi, 1e2, 1e2 * kTickTolerance);
  AutoRange(1e-3, 1e-3, Scale::kLog, &lo, &hi);
  EXPECT_NEAR(lo, 1e-3, 1e-3 * kTickTolerance);
  EXPECT_NEAR(hi, 1e-2, 1e-2 * kTickTolerance);
  AutoRange(0.3, 9.7, Scale::kLinear, &lo, &hi);
  EXPECT_DOUBLE_EQ(lo, 0.0);
  EXPECT_DOUBLE_EQ(hi, 10.0);
  AutoRange(5.0, 5.0, Scale::kLinear, &lo, &hi);
  EXPECT_LE(lo, 4.5);
  EXPECT_GE(hi, 5.5);
}

TEST(RenderSvg, WellFormedAndDeterministic) {
  const std::string svg = RenderSvg(AllanLikeFigure());
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_EQ(svg, RenderSvg(AllanLikeFigure()));
  splinecal::testing::ExpectContainsEach(svg,
                                         {"<svg xmlns=\"http://www.w3.org/2000/svg\"",
                                          ">Allan deviation [rad/s]</text>",
                                          // Decade labels with superscript exponents on both axes.
                                          ">10<tspan dy=\"-5\" font-size=\"8\">-3</tspan></text>",
                                          ">10<tspan dy=\"-5\" font-size=\"8\">2</tspan></text>",
                                          "stroke-dasharray",
                                          "white noise N = 1.7e-4 rad/s/√Hz"});
  // 30 error bars: a vertical bar and two caps each.
  EXPECT_GE(Count(svg, "V"), 30);
}

TEST(RenderSvg, NeverWritesNonFiniteNumbers) {
  Figure figure;
  Panel& panel = figure.panels.emplace_back();
  panel.x.scale = Scale::kLog;
  panel.y.scale = Scale::kLog;
  Series& series = panel.series.emplace_back();
  series.marker = Marker::kSquare;
  series.x = {1.0, 2.0, kNaN, 4.0, 5.0, -6.0, 7.0, 8.0, kInf};
  series.y = {1.0, 2.0, 3.0, 4.0, 0.0, 6.0, 7.0, kNaN, 9.0};
  series.y_low = {0.5, kNaN, 1.0, -1.0, 1.0, 1.0, 1.0, 1.0, 1.0};
  series.y_high = {2.0, 3.0, kInf, 5.0, 1.0, 1.0, 8.0, 1.0, 1.0};
  const std::string svg = RenderSvg(figure);
  EXPECT_EQ(XmlProblem(svg), "");
  std::string lower = svg;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  EXPECT_THAT(lower, Not(HasSubstr("nan")));
  EXPECT_THAT(lower, Not(HasSubstr("inf")));
  // Valid runs: (1,1)-(2,2), (4,4), (7,7): the line breaks at every bad point.
  EXPECT_EQ(Count(svg, "<polyline"), 1);
  EXPECT_LT(LargestNumber(svg), 1e4);
}

TEST(RenderSvg, ClipsPointsFarOutsideAGivenRange) {
  Figure figure;
  Panel& panel = figure.panels.emplace_back();
  panel.x = {"t [s]", Scale::kLinear, 0.0, 1.0};
  panel.y = {"r [m]", Scale::kLinear, -1.0, 1.0};
  Series& series = panel.series.emplace_back();
  series.marker = Marker::kCircle;
  series.x = {0.0, 0.5, 1e300, 0.75, 1.0};
  series.y = {0.0, 0.5, -1e300, 0.2, 5.0};
  const std::string svg = RenderSvg(figure);
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_LT(LargestNumber(svg), 1e4);
  // (0,0)-(0.5,0.5)-edge toward the far point; edge-(0.75,0.2)-top edge toward (1,5).
  EXPECT_EQ(Count(svg, "<polyline"), 2);
}

TEST(RenderSvg, EscapesText) {
  Figure figure;
  figure.title = "a < b & \"c\"";
  Panel& panel = figure.panels.emplace_back();
  panel.title = "<script>";
  Series& series = panel.series.emplace_back();
  series.label = "x & y";
  series.x = {0.0, 1.0};
  series.y = {0.0, 1.0};
  const std::string svg = RenderSvg(figure);
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_THAT(svg, HasSubstr("a &lt; b &amp; &quot;c&quot;"));
  EXPECT_THAT(svg, HasSubstr("&lt;script&gt;"));
  EXPECT_THAT(svg, HasSubstr(">x &amp; y</text>"));
}

TEST(RenderSvg, GridOfPanels) {
  Figure figure;
  figure.title = "six panels";
  figure.columns = 3;
  for (int p = 0; p < 6; ++p) {
    Panel& panel = figure.panels.emplace_back();
    panel.title = "panel " + std::to_string(p);
    Series& series = panel.series.emplace_back();
    series.x = {0.0, 1.0, 2.0};
    series.y = {1.0 * p, p + 1.0, p * 0.5};
  }
  const std::string svg = RenderSvg(figure);
  EXPECT_EQ(XmlProblem(svg), "");
  EXPECT_EQ(Count(svg, "<g transform=\"translate("), 6);
  EXPECT_THAT(svg, HasSubstr("width=\"1320.00\" height=\"690.00\""));  // 3 x 440, 30 + 2 x 330
  EXPECT_THAT(svg, HasSubstr("<g transform=\"translate(880.00,360.00)\">"));
  // Clip paths have distinct ids.
  for (int p = 0; p < 6; ++p) {
    EXPECT_EQ(Count(svg, "id=\"plot-area-" + std::to_string(p) + "\""), 1);
  }
}

TEST(RenderSvg, EqualAspectWidensTheShorterRange) {
  Figure figure;
  Panel& panel = figure.panels.emplace_back();
  panel.equal_aspect = true;
  panel.legend = LegendPosition::kNone;
  Series& series = panel.series.emplace_back();
  series.x = {0.0, 10.0};
  series.y = {0.0, 1.0};
  const std::string svg = RenderSvg(figure);
  // x spans [0, 10] over 342 px; y over 256 px then spans 7.5 around 0.5: ticks -3 .. 4.
  EXPECT_THAT(svg, HasSubstr(">-3</text>"));
  EXPECT_THAT(svg, HasSubstr(">4</text>"));
  panel.equal_aspect = false;
  EXPECT_THAT(RenderSvg(figure), Not(HasSubstr(">-3</text>")));
}

TEST(RenderSvg, IdPrefixNamesEveryClipPath) {
  Figure figure;
  figure.id_prefix = "fig3";
  figure.panels.emplace_back();
  figure.panels.emplace_back();
  const std::string svg = RenderSvg(figure);
  EXPECT_EQ(XmlProblem(svg), "");
  for (int p = 0; p < 2; ++p) {
    const std::string id = "fig3-area-" + std::to_string(p);
    EXPECT_EQ(Count(svg, "id=\"" + id + "\""), 1);
    EXPECT_EQ(Count(svg, "url(#" + id + ")"), 1);
  }
  EXPECT_THAT(svg, Not(HasSubstr("plot-area")));
}

TEST(RenderSvg, ReversedAxisPutsLargeValuesAtTheBottom) {
  Figure figure;
  Panel& panel = figure.panels.emplace_back();
  panel.y = {"v [px]", Scale::kLinear, 0.0, 10.0};
  // The plot area spans y = 28 (top) to 284 (bottom) px; tick labels sit 4 px below their tick.
  EXPECT_THAT(RenderSvg(figure), HasSubstr("y=\"32.00\" text-anchor=\"end\">10</text>"));
  panel.y.reversed = true;
  const std::string svg = RenderSvg(figure);
  EXPECT_THAT(svg, HasSubstr("y=\"288.00\" text-anchor=\"end\">10</text>"));
  EXPECT_THAT(svg, HasSubstr("y=\"32.00\" text-anchor=\"end\">0</text>"));
}

TEST(RenderSvg, EmptyFigureIsStillADocument) {
  EXPECT_EQ(XmlProblem(RenderSvg(Figure())), "");
  Figure figure;
  figure.panels.emplace_back();  // no series: default ranges
  EXPECT_EQ(XmlProblem(RenderSvg(figure)), "");
}

}  // namespace
}  // namespace plot
}  // namespace splinecal
