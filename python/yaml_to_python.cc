#include "yaml_to_python.h"

#include <yaml-cpp/yaml.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <regex>

namespace splinecal {
namespace python {

namespace py = pybind11;

namespace {

py::object PlainScalar(const std::string& text) {
  // YAML 1.2 core schema (https://yaml.org/spec/1.2.2/#103-core-schema).
  static const std::regex kNull("null|Null|NULL|~|");
  static const std::regex kTrue("true|True|TRUE");
  static const std::regex kFalse("false|False|FALSE");
  static const std::regex kInt("[-+]?[0-9]+");
  static const std::regex kFloat(R"([-+]?(\.[0-9]+|[0-9]+(\.[0-9]*)?)([eE][-+]?[0-9]+)?)");
  static const std::regex kInf(R"([-+]?\.(inf|Inf|INF))");
  static const std::regex kNan(R"(\.(nan|NaN|NAN))");
  if (std::regex_match(text, kNull)) return py::none();
  if (std::regex_match(text, kTrue)) return py::bool_(true);
  if (std::regex_match(text, kFalse)) return py::bool_(false);
  if (std::regex_match(text, kInt)) return py::int_(py::str(text));  // any size, exactly
  if (std::regex_match(text, kFloat)) return py::float_(std::strtod(text.c_str(), nullptr));
  if (std::regex_match(text, kInf)) {
    return py::float_(text[0] == '-' ? -std::numeric_limits<double>::infinity()
                                     : std::numeric_limits<double>::infinity());
  }
  if (std::regex_match(text, kNan)) return py::float_(std::numeric_limits<double>::quiet_NaN());
  return py::str(text);
}

py::object ToPython(const YAML::Node& node) {
  switch (node.Type()) {
    case YAML::NodeType::Map: {
      py::dict dict;
      for (const auto& item : node) dict[py::str(item.first.Scalar())] = ToPython(item.second);
      return std::move(dict);
    }
    case YAML::NodeType::Sequence: {
      py::list list;
      for (const auto& item : node) list.append(ToPython(item));
      return std::move(list);
    }
    case YAML::NodeType::Scalar:
      // yaml-cpp tags a quoted scalar "!": always a string, even "1".
      return node.Tag() == "!" ? py::str(node.Scalar()) : PlainScalar(node.Scalar());
    default:
      return py::none();
  }
}

}  // namespace

py::dict YamlTextToDict(const std::string& yaml_text) {
  py::object object = ToPython(YAML::Load(yaml_text));
  if (!py::isinstance<py::dict>(object)) return py::dict();
  return object.cast<py::dict>();
}

}  // namespace python
}  // namespace splinecal
