#include "splinecal/report/html_page.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <string>

#include "testing/html_ids.h"
#include "testing/text_checks.h"

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
  testing::ExpectContainsEach(html,
                              {"<title>a &lt;b&gt; &amp; c</title>",
                               "<h1>a &lt;b&gt; &amp; c</h1>\n",
                               // The report's layout comes last: it overrides the shared rules.
                               "body{margin:2em}</style>",
                               "<style>body{font-family:sans-serif}"});
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

TEST(HtmlPage, FiguresInlineWithoutXmlDeclarationAndWithTheirOwnIds) {
  plot::Figure figure;
  figure.panels.emplace_back();
  figure.panels.emplace_back();
  ASSERT_THAT(plot::RenderSvg(figure), StartsWith("<?xml"));
  HtmlPage page("t", "");
  // The same figure twice: the second must not reuse the first one's clip path ids (HTML ids are
  // global to the page; a panel would be clipped by the other figure's rectangle).
  page.FigureSection("A", figure);
  page.FigureSection("B", figure);
  const std::string html = page.str();
  EXPECT_THAT(html, HasSubstr("<h2>A</h2>\n<svg"));
  EXPECT_THAT(html, Not(HasSubstr("<?xml")));
  EXPECT_EQ(testing::ExpectUniqueHtmlIds(html), 4);
  EXPECT_THAT(html, HasSubstr("id=\"fig2-area-1\""));
}

}  // namespace
}  // namespace splinecal
