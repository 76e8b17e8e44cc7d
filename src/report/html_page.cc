#include "splinecal/report/html_page.h"

#include <string>

namespace splinecal {

namespace {

// Shared by every report; each adds its layout after it (HtmlPage's constructor).
constexpr char kSharedCss[] =
    "body{font-family:sans-serif}table{border-collapse:collapse}td,th{border:1px solid #ccc}";

}  // namespace

HtmlPage::HtmlPage(const std::string& title, const std::string& layout_css) {
  const std::string escaped = plot::EscapeXml(title);
  html_ = "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" + escaped +
          "</title>\n<style>" + kSharedCss + layout_css + "</style></head><body>\n<h1>" + escaped +
          "</h1>\n";
}

void HtmlPage::Append(const std::string& html) { html_ += html; }

void HtmlPage::Section(const std::string& heading, const std::string& html) {
  html_ += "<h2>" + plot::EscapeXml(heading) + "</h2>\n" + html + "\n";
}

void HtmlPage::ListSection(const std::string& heading,
                           const std::vector<std::string>& items,
                           const std::string& list_class) {
  if (items.empty()) return;
  html_ += "<h2>" + plot::EscapeXml(heading) + "</h2>\n<ul";
  if (!list_class.empty()) html_ += " class=\"" + plot::EscapeXml(list_class) + "\"";
  html_ += ">\n";
  for (const std::string& item : items) html_ += "<li>" + plot::EscapeXml(item) + "</li>\n";
  html_ += "</ul>\n";
}

void HtmlPage::FigureSection(const std::string& heading, plot::Figure figure) {
  figure.id_prefix = "fig" + std::to_string(++num_figures_);
  std::string svg = plot::RenderSvg(figure);
  // An XML declaration is not allowed inside HTML: drop it.
  if (svg.rfind("<?xml", 0) == 0) svg.erase(0, svg.find('\n') + 1);
  Section(heading, svg);
}

std::string HtmlPage::str() const { return html_ + "</body></html>\n"; }

}  // namespace splinecal
