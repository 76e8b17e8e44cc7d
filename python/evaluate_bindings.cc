// splinecal.evaluate: `splinecal evaluate` (report/evaluate_report.h) with every flag as a
// keyword, returning its result.yaml as a dict plus the evaluations at the sample times.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "numpy_io.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/report/evaluate_report.h"

namespace splinecal {
namespace python {

namespace {

py::dict SamplesDict(const std::vector<SplineEvaluation>& samples) {
  std::vector<SE3d> T_w_s;
  for (const SplineEvaluation& e : samples) T_w_s.push_back(e.T_w_s);
  py::dict dict;
  dict["t_ns"] = TimeColumn(samples);
  dict["T_w_s"] = PoseArray(T_w_s);
  dict["w_s"] = Vector3Column(samples, [](const auto& e) { return e.w_s; });
  dict["v_w"] = Vector3Column(samples, [](const auto& e) { return e.v_w; });
  dict["a_w"] = Vector3Column(samples, [](const auto& e) { return e.a_w; });
  dict["gyro"] = Vector3Column(samples, [](const auto& e) { return e.gyro; });
  dict["accel"] = Vector3Column(samples, [](const auto& e) { return e.accel; });
  return dict;
}

py::dict EvaluateFunction(py::handle spline,
                          int samples,
                          double every,
                          double gravity,
                          py::handle gyro_bias,
                          py::handle accel_bias,
                          py::handle out) {
  EvaluateOptions options;
  options.samples = samples;
  options.every_s = NonNegativeArgument(every, "every");
  options.gravity_m_s2 = PositiveArgument(gravity, "gravity");
  options.gyro_bias = Vector3Argument(gyro_bias, "gyro_bias");
  options.accel_bias = Vector3Argument(accel_bias, "accel_bias");
  // A spline.csv path, read as the command reads it, or an SE3Spline (result.yaml's `spline`
  // is then empty: there is no file).
  const std::optional<std::string> file = AsPath(spline);
  if (!file && !py::isinstance<SE3Splined>(spline)) {
    throw py::value_error("spline: expected a spline.csv path or an SE3Spline");
  }
  const std::string path = file.value_or("");
  const SE3Splined curve = file ? ReadSplineCsv(*file) : spline.cast<SE3Splined>();
  CheckEvaluateOptions(curve, options);
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  const EvaluateRun run = EvaluateSplineFiles(curve, path, options);
  py::dict dict = FinishOutputs(output.get(), run.files);
  dict["samples"] = SamplesDict(run.samples);
  return dict;
}

}  // namespace

void BindEvaluate(py::module_& m) {
  const EvaluateOptions defaults;
  DefCommand(m,
             "evaluate",
             &EvaluateFunction,
             R"(`splinecal evaluate` with its flags as keywords: spline (a spline.csv path or an
SE3Spline) at `samples` evenly spaced times of its valid range, and with every > 0 [s] also at
that step (evaluation.csv; SE3Spline.evaluate gives arrays at any times). out: a folder to write
samples.csv, result.yaml and evaluation.csv to. Returns result.yaml's keys plus samples {t_ns,
T_w_s, w_s, v_w, a_w, gyro, accel} at the evenly spaced times.)",
             py::arg("spline"),
             py::kw_only(),
             py::arg("samples") = defaults.samples,
             py::arg("every") = defaults.every_s,
             py::arg("gravity") = defaults.gravity_m_s2,
             py::arg("gyro_bias") = std::vector<double>{0.0, 0.0, 0.0},
             py::arg("accel_bias") = std::vector<double>{0.0, 0.0, 0.0});
}

}  // namespace python
}  // namespace splinecal
