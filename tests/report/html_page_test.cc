#include "splinecal/report/html_page.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

namespace splinecal {
namespace {

using ::testing::EndsWith;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

TEST(HtmlPage, SkeletonWithEscapedTitleAndLayoutAfterTheSharedCss) {
  HtmlPage page("a <b> & c", "body{margin:2em}");
  const std::string html = page.str();
  EXPECT_THAT(html, StartsWith("<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\">"));
  EXPECT_THAT(html, HasSubstr("<title>a &lt;b&gt; &amp; c</title>"));
  EXPECT_THAT(html, HasSubstr("<h1>a &lt;b&gt; &amp; c</h1>\n"));
  // The report's layout comes last, so it overrides the shared rules.
  EXPECT_THAT(html, HasSubstr("body{margin:2em}</style>"));
  EXPECT_THAT(html, HasSubstr("<style>body{font-family:sans-serif}"));
  EXPECT_THAT(html, EndsWith("</body></html>\n"));
}

TEST(HtmlPage, SectionsAndListsInOrder) {
  HtmlPage page("t", "");
  page.Append("<table></table>\n");
  page.ListSection("Warnings", {"x < y"}, "warn");
  page.ListSection("Nothing", {});
  page.Section("Plot", "<svg></svg>");
  const std::string html = page.str();
  EXPECT_THAT(html,
              HasSubstr("<table></table>\n<h2>Warnings</h2>\n<ul class=\"warn\">\n"
                        "<li>x &lt; y</li>\n</ul>\n<h2>Plot</h2>\n<svg></svg>\n</body>"));
  EXPECT_THAT(html, Not(HasSubstr("Nothing")));
}

TEST(InlineSvg, DropsTheXmlDeclaration) {
  plot::Figure figure;
  plot::Panel& panel = figure.panels.emplace_back();
  plot::Series& series = panel.series.emplace_back();
  series.x = {0.0, 1.0};
  series.y = {0.0, 1.0};
  ASSERT_THAT(plot::RenderSvg(figure), StartsWith("<?xml"));
  EXPECT_THAT(InlineSvg(figure), StartsWith("<svg"));
}

}  // namespace
}  // namespace splinecal
