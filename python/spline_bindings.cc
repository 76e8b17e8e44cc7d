// splinecal.SE3Spline: the spline T_w_s(t) of spline/se3_spline.h, read from and written to
// spline.csv (io/spline_csv.h), evaluated at int64 nanosecond times like `splinecal evaluate`.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fstream>

#include "bindings.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace python {

namespace {

// Times to evaluate at: an int or an int64 array (n,), in any order.
std::vector<int64_t> QueryTimes(py::handle t_ns) {
  if (py::isinstance<py::int_>(t_ns)) {
    try {
      return {t_ns.cast<int64_t>()};
    } catch (const py::cast_error&) {
      throw py::value_error("t_ns: " + py::str(t_ns).cast<std::string>() +
                            " does not fit int64 nanoseconds");
    }
  }
  return TimesNs(t_ns, "t_ns", /*increasing=*/false);
}

py::dict Evaluate(const SE3Splined& spline, py::handle t_ns_object) {
  const std::vector<int64_t> t_ns = QueryTimes(t_ns_object);
  std::vector<SE3d> T_w_s(t_ns.size());
  std::vector<Eigen::Vector3d> w_s(t_ns.size()), v_w(t_ns.size()), a_w(t_ns.size());
  RunWithoutGil([&] {
    for (size_t i = 0; i < t_ns.size(); ++i) {
      spline.Evaluate(spline.SegmentAtNs(t_ns[i]), &T_w_s[i], &w_s[i], nullptr, &v_w[i], &a_w[i]);
    }
    return 0;
  });
  py::dict result;
  result["t_ns"] = TimesArray(t_ns);
  result["T_w_s"] = PoseArray(T_w_s);
  result["w_s"] = Vector3Array(w_s);
  result["v_w"] = Vector3Array(v_w);
  result["a_w"] = Vector3Array(a_w);
  return result;
}

py::tuple PredictImuAt(const SE3Splined& spline,
                       py::handle t_ns_object,
                       double gravity,
                       py::handle gyro_bias,
                       py::handle accel_bias) {
  PositiveArgument(gravity, "gravity");
  const std::vector<int64_t> t_ns = QueryTimes(t_ns_object);
  const Eigen::Vector3d g_w = GravityWorld(gravity);
  const Eigen::Vector3d b_g = Vector3Argument(gyro_bias, "gyro_bias");
  const Eigen::Vector3d b_a = Vector3Argument(accel_bias, "accel_bias");
  std::vector<Eigen::Vector3d> gyro(t_ns.size()), accel(t_ns.size());
  RunWithoutGil([&] {
    for (size_t i = 0; i < t_ns.size(); ++i) {
      PredictImu(spline, spline.SegmentAtNs(t_ns[i]), g_w, b_g, b_a, &gyro[i], &accel[i]);
    }
    return 0;
  });
  return py::make_tuple(Vector3Array(gyro), Vector3Array(accel));
}

void WriteCsv(const SE3Splined& spline, py::handle path_object) {
  const std::string path = PathArgument(path_object, "path");
  std::ofstream out(path);
  WriteSplineCsv(spline, &out);
  out.close();
  if (!out) throw Error(path, 0, "cannot write the spline");
}

}  // namespace

void BindSpline(py::module_& m) {
  py::class_<SE3Splined>(m, "SE3Spline", R"(A uniform cubic B-spline T_w_s(t) of SE(3) poses.

Control poses T_i at knot times t0_ns + i * dt_ns; valid times [t_1, t_{n-2}]; interpolated by
the coupled cumulative SE(3) spline (trajectory "se3") or the split SO(3) x R^3 one ("split")
(docs/conventions.md, "The spline").)")
      .def(py::init([](py::handle control_poses,
                       int64_t t0_ns,
                       int64_t dt_ns,
                       const std::string& trajectory) {
             return SE3Splined(PosesFromArray(control_poses, "control_poses"),
                               t0_ns,
                               dt_ns,
                               TrajectoryArgument(trajectory));
           }),
           py::arg("control_poses"),
           py::arg("t0_ns"),
           py::arg("dt_ns"),
           py::kw_only(),
           py::arg("trajectory") = "se3",
           "From control poses (n, 4, 4), n >= 4, the first knot time and the knot spacing [ns];\n"
           "trajectory: se3 or split.")
      .def_static(
          "read_csv",
          [](py::handle path) { return ReadSplineCsv(PathArgument(path, "path")); },
          py::arg("path"),
          "Reads a spline.csv (#t_ns,px,py,pz,qw,qx,qy,qz; its trajectory model from the\n"
          "'# trajectory:' line, se3 without one), as `splinecal evaluate` does.")
      .def("write_csv", &WriteCsv, py::arg("path"), "Writes the control poses as spline.csv.")
      .def(
          "valid_range_ns",
          [](const SE3Splined& s) { return py::make_tuple(s.start_time_ns(), s.end_time_ns()); },
          "(t_1, t_{n-2}) [ns]: the times evaluate() accepts, both ends included.")
      .def_property_readonly("t0_ns", &SE3Splined::t0_ns)
      .def_property_readonly("dt_ns", &SE3Splined::dt_ns)
      .def_property_readonly("num_control_poses", &SE3Splined::num_control_poses)
      .def_property_readonly(
          "trajectory",
          [](const SE3Splined& s) { return std::string(TrajectoryModelName(s.model())); },
          "The trajectory model: se3 or split.")
      .def_property_readonly(
          "control_poses",
          [](const SE3Splined& s) { return PoseArray(s.control_poses()); },
          "The control poses T_w_i, (n, 4, 4).")
      .def("evaluate",
           &Evaluate,
           py::arg("t_ns"),
           R"(The spline at int64 times [ns]: a dict of t_ns (n,), T_w_s (n, 4, 4),
w_s (n, 3) body angular velocity [rad/s], v_w (n, 3) [m/s] and a_w (n, 3) [m/s^2].)")
      .def("predict_imu",
           &PredictImuAt,
           py::arg("t_ns"),
           py::arg("gravity") = kDefaultGravity,
           py::arg("gyro_bias") = std::vector<double>{0.0, 0.0, 0.0},
           py::arg("accel_bias") = std::vector<double>{0.0, 0.0, 0.0},
           R"((gyro, accel), each (n, 3): the IMU reading the spline predicts,
gyro = w_s + b_g [rad/s], accel = R_w_s^T (a_w - g_w) + b_a [m/s^2], g_w = (0, 0, -gravity).)")
      .def("__repr__", [](const SE3Splined& s) {
        return "SE3Spline(" + std::to_string(s.num_control_poses()) +
               " control poses, t0_ns=" + std::to_string(s.t0_ns()) +
               ", dt_ns=" + std::to_string(s.dt_ns()) +
               ", trajectory=" + TrajectoryModelName(s.model()) + ")";
      });
}

}  // namespace python
}  // namespace splinecal
