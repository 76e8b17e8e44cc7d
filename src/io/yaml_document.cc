#include "splinecal/io/yaml_document.h"

#include <cmath>
#include <sstream>

#include <yaml-cpp/yaml.h>

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

  // Walks "a/b/c"; on a missing key throws naming the deepest map that exists.
  YAML::Node Find(const std::string& key_path, bool required) const {
    // yaml-cpp: Node::operator= writes through to the referenced node and non-const operator[]
    // inserts missing keys, so walk with reset() on const views.
    YAML::Node node;
    node.reset(root);
    std::stringstream keys(key_path);
    std::string key;
    while (std::getline(keys, key, '/')) {
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
    double value = 0.0;
    size_t used = 0;
    try {
      value = std::stod(text, &used);
    } catch (const std::exception&) {
      used = 0;
    }
    if (used == 0 || used != text.size()) {
      throw Error(path, LineOf(node), "'" + key_path + "' must be a number, got '" + text + "'");
    }
    if (!std::isfinite(value)) {
      throw Error(path, LineOf(node), "'" + key_path + "' is not finite");
    }
    return value;
  }
};

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
    throw Error(path, e.mark.line >= 0 ? e.mark.line + 1 : 0, "invalid YAML: " + e.msg,
                e.mark.column >= 0 ? e.mark.column + 1 : 0);
  }
  if (!impl_->root.IsMap()) throw Error(path, 0, "expected a YAML map of keys");
}

YamlDocument::~YamlDocument() = default;
YamlDocument::YamlDocument(YamlDocument&&) noexcept = default;

const std::string& YamlDocument::path() const { return impl_->path; }

bool YamlDocument::Has(const std::string& key_path) const {
  return impl_->Find(key_path, false).IsDefined();
}

double YamlDocument::Number(const std::string& key_path) const {
  return impl_->ScalarNumber(impl_->Find(key_path, true), key_path);
}

double YamlDocument::PositiveNumber(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  const double value = impl_->ScalarNumber(node, key_path);
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

std::vector<double> YamlDocument::Numbers(const std::string& key_path) const {
  const YAML::Node node = impl_->Find(key_path, true);
  if (!node.IsSequence()) {
    throw Error(impl_->path, impl_->LineOf(node), "'" + key_path + "' must be a list of numbers");
  }
  std::vector<double> values;
  for (const YAML::Node& item : node) values.push_back(impl_->ScalarNumber(item, key_path));
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
      throw Error(impl_->path, impl_->LineOf(node),
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

}  // namespace splinecal
