// YAML as a strict parser reads it: a mapping whose key repeats is an error. yaml-cpp's
// YAML::Load accepts such a document and silently keeps one of the values (PyYAML, yaml-cpp and
// Go's yaml.v2 disagree on which one; ruamel and yaml.v3 refuse the file), so every YAML file
// splinecal writes is checked here for repeated keys before the tests read it.
//
//   const YAML::Node result = testing::LoadStrictYaml(text);   // ADD_FAILURE per repeated key
//   testing::ExpectStrictYamlFilesIn(out_dir);                  // every *.yaml below out_dir
#ifndef SPLINECAL_TESTS_TESTING_STRICT_YAML_H_
#define SPLINECAL_TESTS_TESTING_STRICT_YAML_H_

#include <gtest/gtest.h>
#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/mark.h>
#include <yaml-cpp/parser.h>
#include <yaml-cpp/yaml.h>

#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

// Follows yaml-cpp's parse events with a stack of open collections; in a mapping, every other
// node is a key, remembered with its line until the mapping ends.
class DuplicateKeyFinder : public YAML::EventHandler {
 public:
  // "line L: key 'k' repeats (first at line F)", one per repeated key, in document order.
  const std::vector<std::string>& problems() const { return problems_; }

  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark& mark, YAML::anchor_t) override { Node(mark, "~"); }
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override { Node(mark, "*alias"); }
  void OnScalar(const YAML::Mark& mark,
                const std::string&,
                YAML::anchor_t,
                const std::string& value) override {
    Node(mark, value);
  }
  void OnSequenceStart(const YAML::Mark& mark,
                       const std::string&,
                       YAML::anchor_t,
                       YAML::EmitterStyle::value) override {
    Open(mark, /*is_map=*/false);
  }
  void OnSequenceEnd() override { open_.pop_back(); }
  void OnMapStart(const YAML::Mark& mark,
                  const std::string&,
                  YAML::anchor_t,
                  YAML::EmitterStyle::value) override {
    Open(mark, /*is_map=*/true);
  }
  void OnMapEnd() override { open_.pop_back(); }

 private:
  struct Collection {
    bool is_map;
    bool next_is_key;                      // maps alternate key, value, key, ...
    std::map<std::string, int> key_lines;  // the keys seen so far and their (1-based) lines
  };

  // A collection starts: a node of its parent, then the innermost open collection. (As a key it
  // is named by its kind only: splinecal never writes one.)
  void Open(const YAML::Mark& mark, bool is_map) {
    Node(mark, is_map ? "{map}" : "[sequence]");
    open_.push_back({is_map, true, {}});
  }

  // A node starts (scalar, null, alias or a collection) in the innermost open collection.
  void Node(const YAML::Mark& mark, const std::string& text) {
    if (open_.empty() || !open_.back().is_map) return;
    Collection& map = open_.back();
    const bool is_key = map.next_is_key;
    map.next_is_key = !map.next_is_key;
    if (!is_key) return;
    const int line = mark.line + 1;
    const auto [it, inserted] = map.key_lines.emplace(text, line);
    if (!inserted) {
      problems_.push_back("line " + std::to_string(line) + ": key '" + text +
                          "' repeats (first at line " + std::to_string(it->second) + ")");
    }
  }

  std::vector<Collection> open_;
  std::vector<std::string> problems_;
};

// The repeated keys of every document in `text` (empty: none); a syntax error is one problem.
inline std::vector<std::string> DuplicateYamlKeys(const std::string& text) {
  std::istringstream in(text);
  DuplicateKeyFinder finder;
  try {
    YAML::Parser parser(in);
    while (parser.HandleNextDocument(finder)) {
    }
  } catch (const YAML::Exception& e) {
    return {std::string("not YAML: ") + e.what()};
  }
  return finder.problems();
}

// YAML::Load(text), with a test failure (naming `name`) for every repeated key.
inline YAML::Node LoadStrictYaml(const std::string& text, const std::string& name = "YAML") {
  for (const std::string& problem : DuplicateYamlKeys(text)) {
    ADD_FAILURE() << name << ": " << problem << "\n" << text;
  }
  return YAML::Load(text);
}

inline YAML::Node LoadStrictYamlFile(const std::string& path) {
  return LoadStrictYaml(ReadFileText(path), path);
}

// Checks every *.yaml file below `dir` (a command's --out folder) as LoadStrictYaml does and
// returns how many there were, so that a caller can expect the files it knows of.
inline int ExpectStrictYamlFilesIn(const std::string& dir) {
  int count = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(dir)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".yaml") continue;
    LoadStrictYamlFile(entry.path().string());
    ++count;
  }
  return count;
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_TESTING_STRICT_YAML_H_
