// The parts of the Python module `splinecal` (docs/python.md), one function per area, each
// adding its classes and functions to the module. module.cc calls them in this order.
#ifndef SPLINECAL_PYTHON_BINDINGS_H_
#define SPLINECAL_PYTHON_BINDINGS_H_

#include <pybind11/pybind11.h>

namespace splinecal {
namespace python {

void BindSpline(pybind11::module_& m);     // SE3Spline (spline_bindings.cc)
void BindAllan(pybind11::module_& m);      // allan_deviation, allan (allan_bindings.cc)
void BindSimulate(pybind11::module_& m);   // simulate (simulate_bindings.cc)
void BindFit(pybind11::module_& m);        // fit (fit_bindings.cc)
void BindCalibrate(pybind11::module_& m);  // calibrate (calibrate_bindings.cc)
void BindDetect(pybind11::module_& m);     // detect (detect_bindings.cc)
void BindIntrinsics(pybind11::module_& m);  // intrinsics (intrinsics_bindings.cc)
void BindEvaluate(pybind11::module_& m);    // evaluate (evaluate_bindings.cc)
void BindIntegrate(pybind11::module_& m);   // integrate (integrate_bindings.cc)
void BindCorrect(pybind11::module_& m);     // correct (correct_bindings.cc)
void BindAlign(pybind11::module_& m);       // align (align_bindings.cc)
void BindExport(pybind11::module_& m);      // export (export_bindings.cc)
void BindBag(pybind11::module_& m);         // bag_info, bag_extract (bag_bindings.cc)

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_BINDINGS_H_
