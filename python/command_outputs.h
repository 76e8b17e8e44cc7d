// A command's files (report/command_outputs.h) on the Python side: result.yaml as a dict, and
// the `out=` keyword that writes all of them the way the command writes --out (io/output_dir.h:
// whole or not at all). The folder is created before the work, as the command creates it, so an
// unwritable `out` fails before a long solve.
#ifndef SPLINECAL_PYTHON_COMMAND_OUTPUTS_H_
#define SPLINECAL_PYTHON_COMMAND_OUTPUTS_H_

#include <pybind11/pybind11.h>

#include <memory>
#include <vector>

#include "splinecal/io/output_dir.h"

namespace splinecal {
namespace python {

// The output folder of `out` (None: none, nullptr), created now.
std::unique_ptr<OutputDir> OutputArgument(pybind11::handle out);

// Writes `files` to `dir` (when not null) and commits them.
void WriteOutputs(OutputDir* dir, const std::vector<OutputFile>& files);
// WriteOutputs, then result.yaml's dict.
pybind11::dict FinishOutputs(OutputDir* dir, const std::vector<OutputFile>& files);

// The keyword `out` (None: nothing written), the last parameter of a command's function.
inline pybind11::arg_v OutArgument() { return pybind11::arg("out") = pybind11::none(); }

// m.def of a command: `definition` is its function, docstring and own arguments (as m.def takes
// them), then comes `out`.
template <typename... Definition>
void DefCommand(pybind11::module_& m, const char* name, const Definition&... definition) {
  m.def(name, definition..., OutArgument());
}

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_COMMAND_OUTPUTS_H_
