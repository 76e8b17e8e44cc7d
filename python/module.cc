// The Python module's entry point: splinecal::Error becomes splinecal.Error (a ValueError: it
// always means bad input), then each area adds its functions (bindings.h).
#include <pybind11/pybind11.h>

#include "bindings.h"
#include "splinecal/error.h"

PYBIND11_MODULE(_splinecal, m) {
  namespace py = pybind11;
  m.doc() = "splinecal: continuous-time spline calibration (docs/python.md)";
  // what() is the command line's one-line message without the "splinecal CMD: " prefix.
  py::register_exception<splinecal::Error>(m, "Error", PyExc_ValueError);
  splinecal::python::BindSpline(m);
  splinecal::python::BindAllan(m);
  splinecal::python::BindSimulate(m);
  splinecal::python::BindFit(m);
  splinecal::python::BindCalibrate(m);
  splinecal::python::BindDetect(m);
  splinecal::python::BindIntrinsics(m);
  splinecal::python::BindEvaluate(m);
  splinecal::python::BindIntegrate(m);
  splinecal::python::BindCorrect(m);
  splinecal::python::BindAlign(m);
  splinecal::python::BindExport(m);
  splinecal::python::BindBag(m);
}
