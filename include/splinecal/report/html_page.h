// The page every splinecal HTML report is written on (report.html of `fit` and `calibrate`):
// one skeleton (doctype, UTF-8, title, the <h1> heading) and one shared style sheet, so that the
// reports look alike and a change of style is made once. The reports fill the body with their
// own tables and SVG figures (plot/svg_plot.h).
//
//   HtmlPage page("splinecal fit", "body{max-width:960px;margin:auto}");
//   page.Append("<table>...</table>\n");
//   page.FigureSection("Residuals", figure);
//   output.WriteFile("report.html", page.str());
//
// Figures go in through FigureSection only: ids (the SVGs' clip paths) are global to an HTML
// document, and the page gives every figure its own id prefix. Two inlined SVGs with the same
// ids clip each other's panels (a later plot drawn through an earlier panel's rectangle).
#ifndef SPLINECAL_REPORT_HTML_PAGE_H_
#define SPLINECAL_REPORT_HTML_PAGE_H_

#include <string>
#include <vector>

#include "splinecal/plot/svg_plot.h"

namespace splinecal {

// The layout_css of the calibration reports (calibrate, intrinsics): a 1000 px column of tables
// of numbers, right-aligned, with captions.
inline constexpr char kCalibrationReportCss[] =
    "body{margin:2em;max-width:1000px}td,th{padding:3px 8px;text-align:right}"
    "th{text-align:left}caption{text-align:left;padding:4px 0}";

class HtmlPage {
 public:
  // `title` becomes the page's <title> and <h1> (escaped here). `layout_css` follows the shared
  // style sheet (sans-serif text, collapsed table borders), so it can override it: the page
  // width, cell padding and alignment of one report.
  HtmlPage(const std::string& title, const std::string& layout_css);

  // HTML the caller built; text inside it must be escaped (plot::EscapeXml).
  void Append(const std::string& html);
  // <h2>heading</h2> (escaped), then `html` on the next line.
  void Section(const std::string& heading, const std::string& html);
  // Section(heading, the SVG of `figure` inline), its ids prefixed "figN" (N counts the page's
  // figures from 1; the figure's own id_prefix is replaced).
  void FigureSection(const std::string& heading, plot::Figure figure);
  // <h2>heading</h2> and a bullet list of `items` (escaped); `list_class` is the <ul>'s CSS class
  // (empty for none). Writes nothing when `items` is empty.
  void ListSection(const std::string& heading,
                   const std::vector<std::string>& items,
                   const std::string& list_class = "");

  // The whole document, closed.
  std::string str() const;

 private:
  std::string html_;
  int num_figures_ = 0;
};

}  // namespace splinecal

#endif  // SPLINECAL_REPORT_HTML_PAGE_H_
