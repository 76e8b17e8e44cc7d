// The ids of an HTML document, as a browser resolves them: one namespace for the whole page, so
// an id defined twice (two inlined SVGs with the same clip path id) makes every reference to it
// resolve to the first one. Used on every report.html the commands write.
#ifndef SPLINECAL_TESTS_TESTING_HTML_IDS_H_
#define SPLINECAL_TESTS_TESTING_HTML_IDS_H_

#include <gtest/gtest.h>

#include <map>
#include <regex>
#include <set>
#include <string>
#include <vector>

namespace splinecal {
namespace testing {

// The values of every id="..." attribute, in document order.
inline std::vector<std::string> HtmlIds(const std::string& html) {
  std::vector<std::string> ids;
  static const std::regex kId("\\sid=\"([^\"]*)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kId); it != std::sregex_iterator();
       ++it) {
    ids.push_back((*it)[1]);
  }
  return ids;
}

// The ids referenced as url(#id) or href="#id".
inline std::set<std::string> HtmlIdReferences(const std::string& html) {
  std::set<std::string> references;
  static const std::regex kReference("url\\(#([^)]*)\\)|href=\"#([^\"]*)\"");
  for (auto it = std::sregex_iterator(html.begin(), html.end(), kReference);
       it != std::sregex_iterator();
       ++it) {
    references.insert((*it)[1].matched ? (*it)[1] : (*it)[2]);
  }
  return references;
}

// A test failure for every id defined more than once and every reference to an undefined id;
// returns the number of ids (so a caller can check that there are some).
inline int ExpectUniqueHtmlIds(const std::string& html, const std::string& name = "HTML") {
  std::map<std::string, int> count;
  const std::vector<std::string> ids = HtmlIds(html);
  for (const std::string& id : ids) {
    if (++count[id] == 2) ADD_FAILURE() << name << ": id '" << id << "' is defined more than once";
  }
  for (const std::string& reference : HtmlIdReferences(html)) {
    if (count.count(reference) == 0) {
      ADD_FAILURE() << name << ": '#" << reference << "' is referenced but not defined";
    }
  }
  return static_cast<int>(ids.size());
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_HTML_IDS_H_
