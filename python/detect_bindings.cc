// splinecal.detect: the target corners in grayscale images (detect/target_detector.h), the
// per-image step of `splinecal detect` (whose result.yaml summarises folders of images). Images
// come as pixels the caller decoded, or as files that splinecal's own decoder reads
// (detect/image_file.h), so that a file gives the same corners here as in the command line.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <filesystem>

#include "bindings.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/error.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/image_folder.h"
#include "splinecal/io/target_yaml.h"

namespace splinecal {
namespace python {

namespace {

py::dict DetectionDict(const TargetDetection& detection) {
  const auto n = static_cast<py::ssize_t>(detection.corners.size());
  py::array_t<int64_t> point_id(n);
  py::array_t<double> uv({n, py::ssize_t{2}});
  for (py::ssize_t i = 0; i < n; ++i) {
    point_id.mutable_data()[i] = detection.corners[i].point_id;
    uv.mutable_data()[2 * i] = detection.corners[i].uv.x();
    uv.mutable_data()[2 * i + 1] = detection.corners[i].uv.y();
  }
  py::dict dict;
  dict["point_id"] = point_id;
  dict["uv"] = uv;
  dict["tags_found"] = detection.tags_found;
  dict["tags_rejected"] = detection.tags_rejected;
  dict["corners_rejected"] = detection.corners_rejected;
  return dict;
}

// Pixels the caller decoded: a uint8 array (h, w), any memory layout.
py::dict DetectArray(py::handle image_object, TargetDetector* detector) {
  py::array any = py::array::ensure(image_object);
  if (!any) {
    PyErr_Clear();
    throw py::value_error(
        "image: expected a uint8 array (h, w), an image file, a folder or a list of files");
  }
  if (any.dtype().kind() != 'u' || any.itemsize() != 1) {
    throw py::value_error("image: expected dtype uint8 (8-bit grayscale), got dtype " +
                          py::str(any.dtype()).cast<std::string>());
  }
  if (any.ndim() != 2 || any.shape(0) < 1 || any.shape(1) < 1) {
    throw py::value_error("image: expected shape (h, w), got " + std::to_string(any.ndim()) +
                          " dimensions");
  }
  const auto image = py::array_t<uint8_t, py::array::c_style>::ensure(any);
  GrayImageView view;
  view.height = static_cast<int>(image.shape(0));
  view.width = static_cast<int>(image.shape(1));
  view.stride = view.width;
  view.data = image.data();
  return DetectionDict(RunWithoutGil([&] { return detector->Detect(view); }));
}

// One file, decoded as `splinecal detect` decodes it; splinecal.Error naming it when it cannot.
py::dict DetectFile(const std::string& path, TargetDetector* detector) {
  py::dict dict = DetectionDict(RunWithoutGil([&] {
    const GrayImage image = ReadGrayImage(path);
    return detector->Detect(image.view());
  }));
  dict["path"] = path;
  return dict;
}

py::object Detect(py::handle images, py::handle target, const std::string& effort) {
  const CalibrationTarget board = ReadTargetYaml(PathArgument(target, "target"));
  DetectorOptions options;
  try {
    options.effort = ParseDetectEffort(effort);
  } catch (const Error& e) {
    throw py::value_error(std::string("effort: ") + e.what());
  }
  TargetDetector detector(board, options);
  if (const std::optional<std::string> path = AsPath(images)) {
    if (!std::filesystem::is_directory(*path)) return DetectFile(*path, &detector);
    // A camera folder as `splinecal detect --images` lists it: one dict per frame, with its
    // timestamp.
    const ImageFolder folder = ListImageFolder(*path);
    py::list frames;
    for (const ImageFrame& frame : folder.frames) {
      py::dict dict = DetectFile(frame.path, &detector);
      dict["t_ns"] = frame.t_ns;
      frames.append(dict);
    }
    return std::move(frames);
  }
  if (py::isinstance<py::list>(images) || py::isinstance<py::tuple>(images)) {
    // Every item checked before the first file is read.
    std::vector<std::string> paths;
    for (py::handle item : images) {
      const std::optional<std::string> path = AsPath(item);
      if (!path) {
        throw py::value_error("image[" + std::to_string(paths.size()) +
                              "]: expected a path (str or os.PathLike) in a list of files");
      }
      paths.push_back(*path);
    }
    py::list frames;
    for (const std::string& path : paths) frames.append(DetectFile(path, &detector));
    return std::move(frames);
  }
  return DetectArray(images, &detector);
}

}  // namespace

void BindDetect(py::module_& m) {
  m.def("detect",
        &Detect,
        py::arg("image"),
        py::arg("target"),
        py::kw_only(),
        py::arg("effort") = "default",
        R"(Target corners in grayscale images; target: a Kalibr target YAML path.

image: a uint8 array (h, w) of pixels already decoded, or the path of a PNG/JPEG file, or a
list of such paths, or a camera folder as `splinecal detect --images` reads it (EuRoC data.csv
and data/, or <t_ns>.png files). Files are decoded by splinecal's own decoder, as the command
line does, so the same file gives the same corners in both.
effort: "default" (recall first), "thorough" (the upsampled searches in every frame) or
"fast" (one search, misses most tags under 25 px), as `splinecal detect --effort`.

Returns, for an array or a file, a dict: point_id (k,) and uv (k, 2) [px] (pixel centres at
integers, docs/conventions.md), tags_found, tags_rejected, corners_rejected (and path for a
file); for a list of files, a list of such dicts in its order; for a folder, a list in time
order whose dicts also hold t_ns. A file that cannot be read raises splinecal.Error naming it.)");
}

}  // namespace python
}  // namespace splinecal
