// A result.yaml as Python objects. The module's functions return the very text the command line
// writes (AllanResultYamlText, FitResultYaml, ...) parsed into a dict, so the keys and values are
// the command's by construction: maps become dicts, sequences lists, quoted scalars str, plain
// scalars bool, int, float or None where YAML 1.2's core schema says so, str otherwise.
#ifndef SPLINECAL_PYTHON_YAML_TO_PYTHON_H_
#define SPLINECAL_PYTHON_YAML_TO_PYTHON_H_

#include <pybind11/pybind11.h>

#include <string>

namespace splinecal {
namespace python {

pybind11::dict YamlTextToDict(const std::string& yaml_text);

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_YAML_TO_PYTHON_H_
