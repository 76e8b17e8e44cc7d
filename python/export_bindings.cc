// splinecal.export: `splinecal export` (io/calibration_export.h) with every flag as a keyword.
// Returns {file name: text} of the chosen format's files, and writes them to `out` when given.
// The folder flag --from is the keyword `from_` (`from` is a Python keyword).
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "splinecal/error.h"
#include "splinecal/io/calibration_export.h"

namespace splinecal {
namespace python {

namespace py = pybind11;

namespace {

py::dict ExportFunction(const std::string& from,
                        const std::string& format,
                        const std::string& imu_yaml,
                        const std::string& imu_topic,
                        py::handle out) {
  ExportFormat parsed;
  if (!ParseExportFormat(format, &parsed)) {
    throw Error("format '" + format + "': expected one of " + ExportFormatNames());
  }
  CalibrationExport calibration = ReadCalibrationForExport(from, imu_yaml);
  if (imu_topic.empty() || imu_topic[0] != '/') {
    throw Error("imu_topic '" + imu_topic + "': a ROS topic starts with '/'");
  }
  calibration.imu_topic = imu_topic;
  const std::vector<OutputFile> files = ExportCalibration(calibration, parsed);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  WriteOutputs(output.get(), files);
  py::dict dict;
  for (const OutputFile& file : files) dict[py::str(file.path)] = file.contents;
  return dict;
}

}  // namespace

void BindExport(py::module_& m) {
  DefCommand(
      m,
      "export",
      &ExportFunction,
      R"(`splinecal export` with its flags as keywords: the calibration folder from_ (calibrate's
or intrinsics' output) in the files of format 'openvins', 'vins', 'basalt' or 'kalibr'. imu_yaml:
the noise densities (default: the folder's imu.yaml, else result.yaml's). out: a folder to write
them to. Returns {file name: contents}.)",
      py::arg("from_"),
      py::kw_only(),
      py::arg("format"),
      py::arg("imu_yaml") = "",
      py::arg("imu_topic") = "/imu0");
}

}  // namespace python
}  // namespace splinecal
