#include "command_outputs.h"

#include "numpy_io.h"
#include "yaml_to_python.h"

namespace splinecal {
namespace python {

std::unique_ptr<OutputDir> OutputArgument(py::handle out) {
  if (out.is_none()) return nullptr;
  return std::make_unique<OutputDir>(PathArgument(out, "out"));
}

void WriteOutputs(OutputDir* dir, const std::vector<OutputFile>& files) {
  if (dir == nullptr) return;
  dir->WriteFiles(files);
  dir->Commit();
}

py::dict FinishOutputs(OutputDir* dir, const std::vector<OutputFile>& files) {
  WriteOutputs(dir, files);
  return YamlTextToDict(OutputFileContents(files, "result.yaml"));
}

}  // namespace python
}  // namespace splinecal
