// splinecal.detect: the target corners in one grayscale image (detect/target_detector.h), the
// per-image step of `splinecal detect` (whose result.yaml summarises folders of images).
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/detect/target_detector.h"
#include "splinecal/io/target_yaml.h"

namespace splinecal {
namespace python {

namespace {

py::dict Detect(py::handle image_object, py::handle target) {
  const CalibrationTarget board = ReadTargetYaml(PathArgument(target, "target"));
  py::array any = py::array::ensure(image_object);
  if (!any) {
    PyErr_Clear();
    throw py::value_error("image: expected a uint8 array (h, w)");
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
  const TargetDetection detection = RunWithoutGil([&] { return DetectTargetCorners(view, board); });
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

}  // namespace

void BindDetect(py::module_& m) {
  m.def("detect",
        &Detect,
        py::arg("image"),
        py::arg("target"),
        R"(Target corners in a grayscale image (h, w) uint8; target: a Kalibr target YAML path.
Returns point_id (k,) and uv (k, 2) [px] (pixel centres at integers, docs/conventions.md),
tags_found, tags_rejected and corners_rejected.)");
}

}  // namespace python
}  // namespace splinecal
