#include "splinecal/io/yaml_document.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>

#include "splinecal/error.h"
#include "splinecal/io/text_file.h"

namespace splinecal {

struct YamlDocument::Impl {
  std::string path;
  YAML::Node root;

  int64_t LineOf(const YAML::Node& node) const {
    const YAML::Mark mark = node.Mark();
    return mark.line >= 0 ? mark.line + 1 : 0;
  }

  // Walks "a/b/c" (a number steps into a sequence: "points/2"); on a missing key throws naming
  // the deepest map that exists.
  YAML::Node Find(const std::string& key_path, bool required) const {
    // yaml-cpp: Node::operator= writes through to the referenced node and non-const operator[]
    // inserts missing keys, so walk with reset() on const views.
    YAML::Node node;
    node.reset(root);
    std::stringstream keys(key_path);
    std::string key;
    while (std::getline(keys, key, '/')) {
      if (node.IsSequence() && !key.empty() && key.size() < 10 &&
          key.find_first_not_of("0123456789") == std::string::npos) {
        const size_t index = std::stoul(key);
        if (index >= node.size()) {
          if (!required) return YAML::Node(YAML::NodeType::Undefined);
          throw Error(path, LineOf(node), "missing item '" + key_path + "'");
        }
        const YAML::Node& const_node = node;
        node.reset(const_node[index]);
        continue;
      }
      if (!node.IsMap()) {
        if (!required) return YAML::Node(YAML::NodeType::Undefined);
        throw Error(path, LineOf(node), "expected a map holding '" + key + "'");
      }
      const YAML::Node& const_node = node;
      const YAML::Node child = const_node[key];
      if (!child.IsDefined() || child.IsNull()) {
        if (!required) return YAML::Node(YAML::NodeType::Undefined);
        throw Error(path, LineOf(node), "missing key '" + key_path + "'");
      }
      node.reset(child);
    }
    return node;
  }

  double ScalarNumber(const YAML::Node& node, const std::string& key_path) const {
    if (!node.IsScalar()) throw Error(path, LineOf(node), "'" + key_path + "' must be a number");
    const std::string text = node.Scalar();
    // YAML spells the non-finite values .nan and .inf, which strtod does not read.
    std::string lower = text;
    for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    const bool yaml_non_finite =
        lower == ".nan" || lower == ".inf" || lower == "+.inf" || lower == "-.inf";
    char* end = nullptr;
    const double value = std::strtod(text.c_str(), &end);
    if (!yaml_non_finite && (text.empty() || end != text.c_str() + text.size())) {
      throw Error(path, LineOf(node), "'" + key_path + "' must be a number, got '" + text + "'");
    }
    // Overflow (1e999) reads as infinity.
    if (yaml_non_finite || !std::isfinite(value)) {
      throw Error(path, LineOf(node), "'" + key_path + "' is not finite: got '" + text + "'");
    }
    return value;
  }

  double Bounded(const YAML::Node& node,
                 const std::string& key_path,
                 double max_abs,
                 const char* unit) const {
    const double value = ScalarNumber(node, key_path);
    if (std::abs(value) > max_abs) {
      std::ostringstream message;  // %g-style numbers, as the table readers print them
      message << "'" << key_path << "' value " << value << " is beyond the plausible " << max_abs
              << " " << unit;
      throw Error(path, LineOf(node), message.str());
    }
    return value;
  }
};

namespace {

// True when `key` looks like a typo of `known`: the same but for case, or one edit away (two for
// keys of 8 letters or more; none for keys shorter than 4, which are too alike).
bool NearMiss(const std::string& key, const std::string& known) {
  auto lower = [](std::string text) {
    for (char& c : text) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return text;
  };
  const std::string a = lower(key);
  const std::string b = lower(known);
  const size_t allowed = b.size() >= 8 ? 2 : b.size() >= 4 ? 1 : 0;
  if ((a.size() > b.size() ? a.size() - b.size() : b.size() - a.size()) > allowed) return false;
  // Levenshtein distance, one row at a time.
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = above;
    }
  }
  return row[b.size()] <= allowed;
}

}  // namespace

YamlDocument::YamlDocument(const std::string& path) : impl_(new Impl) {
  impl_->path = path;
  std::string text = ReadWholeFile(path);
  // OpenCV writes "%YAML:1.0", which yaml-cpp rejects as a directive; blank it out but keep the
  // line so that line numbers stay right.
  if (text.rfind("%YAML:", 0) == 0) {
    const size_t end = text.find('\n');
    text.replace(0, end == std::string::npos ? text.size() : end, "#");
  }
  try {
    impl_->root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    throw Error(path,
                e.mark.line >= 0 ? e.mark.line + 1 : 0,
                "invalid YAML: " + e.msg,
                e.mark.column >= 0 ? e.mark.column + 1 : 0);
  }
  if (!impl_->root.IsMap()) {
    // Say what the file holds instead: a CSV or other text file given for a YAML one reads as
    // plain text.
    const char* found = impl_->root.IsSequence() ? "a list"
                        : impl_->root.IsScalar() ? "plain text (not 'key: value' lines)"
                                                 : "nothing";
    throw Error(path, 0, std::string("expected a YAML map of keys, found ") + found);
  }
}

YamlDocument::~YamlDocument() = default;
YamlDocument::YamlDocument(YamlDocument&&) noexcept = default;

const std::string& YamlDocument::path() const { return impl_->path; }

bool YamlDocument::Has(const std::string& key_path) const {
  return impl_->Find(key_path, false).IsDefined();
}

int64_t YamlDocument::Line(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, false);
  return node.IsDefined() ? impl_->LineOf(node) : 0;
}

double YamlDocument::Number(const std::string& key_path) const {
  return impl_->ScalarNumber(impl_->Find(key_path, true), key_path);
}

double YamlDocument::BoundedNumber(const std::string& key_path,
                                   double max_abs,
                                   const char* unit) const {
  return impl_->Bounded(impl_->Find(key_path, true), key_path, max_abs, unit);
}

double YamlDocument::PositiveNumber(const std::string& key_path) const {
  return PositiveNumber(key_path, std::numeric_limits<double>::max(), "");
}

double YamlDocument::PositiveNumber(const std::string& key_path,
                                    double max_abs,
                                    const char* unit) const {
  const YAML::Node node = impl_->Find(key_path, true);
  const double value = impl_->Bounded(node, key_path, max_abs, unit);
  if (!(value > 0.0)) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be positive");
  }
  return value;
}

int64_t YamlDocument::Integer(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  const double value = impl_->ScalarNumber(node, key_path);
  if (value != std::floor(value) || std::abs(value) > 9e15) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be an integer");
  }
  return static_cast<int64_t>(value);
}

std::string YamlDocument::String(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  if (!node.IsScalar()) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be a string");
  }
  return node.Scalar();
}

std::vector<std::string> YamlDocument::Strings(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  if (!node.IsSequence()) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be a list of names");
  }
  std::vector<std::string> values;
  for (const YAML::Node& item : node) {
    if (!item.IsScalar()) {
      throw Error(impl_->path, impl_->LineOf(item), "'" + key_path + "': each entry must be a name");
    }
    values.push_back(item.Scalar());
  }
  return values;
}

std::vector<double> YamlDocument::Numbers(const std::string& key_path) const {
  return BoundedNumbers(key_path, std::numeric_limits<double>::max(), "");
}

std::vector<double> YamlDocument::BoundedNumbers(const std::string& key_path,
                                                 double max_abs,
                                                 const char* unit) const {
  const YAML::Node node = impl_->Find(key_path, true);
  if (!node.IsSequence()) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be a list of numbers");
  }
  std::vector<double> values;
  for (const YAML::Node& item : node) {
    values.push_back(impl_->Bounded(item, key_path, max_abs, unit));
  }
  return values;
}

std::vector<std::vector<double>> YamlDocument::Rows(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  std::vector<std::vector<double>> rows;
  if (node.IsMap() && node["rows"] && node["cols"] && node["data"]) {  // OpenCV matrix
    const int64_t n_rows = Integer(key_path + "/rows");
    const int64_t n_cols = Integer(key_path + "/cols");
    const std::vector<double> data = Numbers(key_path + "/data");
    if (n_rows <= 0 || n_cols <= 0 || static_cast<int64_t>(data.size()) != n_rows * n_cols) {
      throw Error(impl_->path,
                  impl_->LineOf(node),
                  "'" + key_path + "': data does not hold rows x cols numbers");
    }
    for (int64_t r = 0; r < n_rows; ++r) {
      rows.emplace_back(data.begin() + r * n_cols, data.begin() + (r + 1) * n_cols);
    }
    return rows;
  }
  if (!node.IsSequence()) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be a list of rows");
  }
  for (const YAML::Node& row : node) {
    if (!row.IsSequence()) {
      throw Error(impl_->path, impl_->LineOf(row), "'" + key_path + "': each row must be a list");
    }
    std::vector<double> values;
    for (const YAML::Node& item : row) values.push_back(impl_->ScalarNumber(item, key_path));
    if (!rows.empty() && values.size() != rows.front().size()) {
      throw Error(impl_->path, impl_->LineOf(row), "'" + key_path + "': rows of unequal length");
    }
    rows.push_back(values);
  }
  return rows;
}

std::vector<std::string> YamlDocument::TopLevelKeys() const {
  std::vector<std::string> keys;
  for (const auto& item : impl_->root) keys.push_back(item.first.Scalar());
  return keys;
}

void YamlDocument::CheckTypos(const std::string& map_path,
                              const std::vector<std::string>& known) const {
  YAML::Node map;
  map.reset(map_path.empty() ? impl_->root : impl_->Find(map_path, false));
  if (!map.IsMap()) return;
  const std::string prefix = map_path.empty() ? "" : map_path + "/";
  for (const auto& item : map) {
    if (!item.first.IsScalar()) continue;
    const std::string key = item.first.Scalar();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    for (const std::string& candidate : known) {
      if (Has(prefix + candidate) || !NearMiss(key, candidate)) continue;
      throw Error(impl_->path,
                  impl_->LineOf(item.first),
                  "unknown key '" + prefix + key + "': did you mean '" + candidate + "'?");
    }
  }
}

}  // namespace splinecal
