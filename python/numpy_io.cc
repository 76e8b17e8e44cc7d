#include "numpy_io.h"

#include <Eigen/LU>
#include <cmath>
#include <limits>

#include "splinecal/imu/imu_rate.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/string_printf.h"

namespace splinecal {
namespace python {

namespace {

// Orthonormality and bottom-row tolerance of a pose matrix: rounding of a float64 rotation is
// ~1e-15; 1e-6 refuses what is not a rotation while accepting matrices printed to 7+ digits.
constexpr double kRotationTolerance = 1e-6;

std::string ShapeText(const std::vector<py::ssize_t>& shape, bool expected) {
  std::string text = "(";
  for (size_t i = 0; i < shape.size(); ++i) {
    if (i > 0) text += ", ";
    // Free lengths read n (rows), then k (columns).
    text += shape[i] < 0 && expected ? (i == 0 ? "n" : "k") : std::to_string(shape[i]);
  }
  return text + (shape.size() == 1 ? ",)" : ")");
}

py::array AnyArray(py::handle object, const std::string& name) {
  if (object.is_none()) throw py::value_error(name + ": expected an array, got None");
  py::array array = py::array::ensure(object);
  if (!array) {
    PyErr_Clear();
    throw py::value_error(name + ": expected an array");
  }
  return array;
}

void CheckShape(const py::array& array,
                const std::string& name,
                const std::vector<py::ssize_t>& shape) {
  std::vector<py::ssize_t> got(array.shape(), array.shape() + array.ndim());
  bool ok = got.size() == shape.size();
  for (size_t i = 0; ok && i < shape.size(); ++i) {
    ok = shape[i] < 0 ? got[i] >= 1 : got[i] == shape[i];
  }
  if (!ok) {
    throw py::value_error(name + ": expected shape " + ShapeText(shape, true) + ", got " +
                          ShapeText(got, false));
  }
}

}  // namespace

std::optional<std::string> AsPath(py::handle object) {
  if (py::isinstance<py::str>(object) || py::hasattr(object, "__fspath__")) {
    return py::module_::import("os").attr("fspath")(object).cast<std::string>();
  }
  return std::nullopt;
}

std::string PathArgument(py::handle object, const std::string& name) {
  const std::optional<std::string> path = AsPath(object);
  if (!path) throw py::value_error(name + ": expected a path (str or os.PathLike)");
  return *path;
}

std::string CommaListArgument(py::handle object, const std::string& name) {
  if (py::isinstance<py::str>(object)) return object.cast<std::string>();
  if (!py::isinstance<py::sequence>(object)) {
    throw py::type_error(name + ": expected a str (comma-separated) or a list");
  }
  std::string text;
  for (py::handle item : object) {
    if (!py::isinstance<py::str>(item) && !py::isinstance<py::int_>(item)) {
      throw py::type_error(name + ": expected a list of str or int");
    }
    text += (text.empty() ? "" : ",") + py::str(item).cast<std::string>();
  }
  return text;
}

std::vector<std::string> SplitCommaList(const std::string& text,
                                        const std::string& name,
                                        const std::string& entry) {
  std::vector<std::string> items;
  for (size_t begin = 0;;) {
    const size_t comma = text.find(',', begin);
    items.push_back(text.substr(begin, comma - begin));
    if (items.back().empty()) throw py::value_error(name + ": an empty " + entry);
    if (comma == std::string::npos) return items;
    begin = comma + 1;
  }
}

double PositiveArgument(double value, const std::string& name) {
  if (!(value > 0.0) || !std::isfinite(value)) {
    throw py::value_error(name + ": must be a positive number, got " + std::to_string(value));
  }
  return value;
}

double NonNegativeArgument(double value, const std::string& name) {
  if (!(value >= 0.0) || !std::isfinite(value)) {
    throw py::value_error(name + ": must be zero or positive, got " + std::to_string(value));
  }
  return value;
}

Eigen::Vector3d Vector3Argument(py::handle object, const std::string& name) {
  const py::array_t<double> array = DoubleArray(object, name, {3});
  return Eigen::Map<const Eigen::Vector3d>(array.data());
}

py::array_t<double> DoubleArray(py::handle object,
                                const std::string& name,
                                const std::vector<py::ssize_t>& shape) {
  const py::array array = AnyArray(object, name);
  const char kind = array.dtype().kind();
  if (kind != 'f' && kind != 'i' && kind != 'u') {
    throw py::value_error(name + ": expected real numbers (float or int dtype), got dtype " +
                          py::str(array.dtype()).cast<std::string>());
  }
  CheckShape(array, name, shape);
  auto values = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(array);
  const double* data = values.data();
  for (py::ssize_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(data[i])) {
      throw py::value_error(name + ": value " + std::to_string(data[i]) + " at flat index " +
                            std::to_string(i) + " is not finite");
    }
  }
  return values;
}

std::vector<int64_t> TimesNs(py::handle object, const std::string& name, bool increasing) {
  const py::array array = AnyArray(object, name);
  const char kind = array.dtype().kind();
  if (kind != 'i' && kind != 'u') {
    throw py::value_error(name + ": expected int64 nanoseconds (an integer dtype), got dtype " +
                          py::str(array.dtype()).cast<std::string>());
  }
  CheckShape(array, name, {-1});
  if (kind == 'u' && array.itemsize() == 8) {
    // uint64 above INT64_MAX would wrap in the cast below.
    auto raw = py::array_t<uint64_t, py::array::c_style | py::array::forcecast>::ensure(array);
    for (py::ssize_t i = 0; i < raw.size(); ++i) {
      if (raw.data()[i] > static_cast<uint64_t>(std::numeric_limits<int64_t>::max())) {
        throw py::value_error(name + ": time at row " + std::to_string(i) +
                              " does not fit int64 nanoseconds");
      }
    }
  }
  auto values = py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(array);
  std::vector<int64_t> t_ns(values.data(), values.data() + values.size());
  for (size_t i = 1; increasing && i < t_ns.size(); ++i) {
    if (t_ns[i] <= t_ns[i - 1]) {
      throw py::value_error(name + ": timestamps not increasing at row " + std::to_string(i) +
                            " (" + std::to_string(t_ns[i]) + " ns after " +
                            std::to_string(t_ns[i - 1]) + " ns)");
    }
  }
  return t_ns;
}

SE3d PoseFromMatrix(const Eigen::Matrix4d& T, const std::string& name) {
  const Eigen::Matrix3d R = T.topLeftCorner<3, 3>();
  const double orthonormality = (R.transpose() * R - Eigen::Matrix3d::Identity()).norm();
  const double bottom = (T.bottomRows<1>() - Eigen::RowVector4d(0, 0, 0, 1)).norm();
  if (!(orthonormality < kRotationTolerance) || !(R.determinant() > 0.0) ||
      !(bottom < kRotationTolerance)) {
    throw py::value_error(name +
                          StringPrintf(": not a pose [[R, t], [0, 0, 0, 1]] with R a rotation "
                                       "(|R^T R - I| = %.3g, det R = %.6g, bottom row off by %.3g)",
                                       orthonormality,
                                       R.determinant(),
                                       bottom));
  }
  return SE3d::FromMatrix(T);
}

std::vector<SE3d> PosesFromArray(py::handle object, const std::string& name) {
  const py::array_t<double> array = DoubleArray(object, name, {-1, 4, 4});
  auto view = array.unchecked<3>();
  std::vector<SE3d> poses;
  poses.reserve(view.shape(0));
  for (py::ssize_t i = 0; i < view.shape(0); ++i) {
    Eigen::Matrix4d T;
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) T(r, c) = view(i, r, c);
    }
    poses.push_back(PoseFromMatrix(T, name + "[" + std::to_string(i) + "]"));
  }
  return poses;
}

py::object RequiredItem(py::handle dict,
                        const std::string& name,
                        const char* key,
                        const std::string& keys) {
  if (!py::isinstance<py::dict>(dict)) {
    throw py::value_error(name + ": expected a path or a dict with keys " + keys + ", got " +
                          py::str(py::type::of(dict).attr("__name__")).cast<std::string>());
  }
  py::dict d = py::reinterpret_borrow<py::dict>(dict);
  if (!d.contains(key)) {
    throw py::value_error(name + ": expected a dict with keys " + keys + "; '" + key +
                          "' is missing");
  }
  return d[key];
}

std::vector<ImuSample> ImuSamples(py::handle imu, const ImuReadOptions& read) {
  if (const std::optional<std::string> path = AsPath(imu)) return ReadEurocImu(*path, read);
  const std::string keys = "t_ns, gyro, accel";
  const std::vector<int64_t> t_ns =
      TimesNs(RequiredItem(imu, "imu", "t_ns", keys), "imu['t_ns']", /*increasing=*/true);
  const auto n = static_cast<py::ssize_t>(t_ns.size());
  const auto gyro = DoubleArray(RequiredItem(imu, "imu", "gyro", keys), "imu['gyro']", {n, 3});
  const auto accel = DoubleArray(RequiredItem(imu, "imu", "accel", keys), "imu['accel']", {n, 3});
  std::vector<ImuSample> samples(t_ns.size());
  for (py::ssize_t i = 0; i < n; ++i) {
    samples[i].t_ns = t_ns[i];
    samples[i].gyro = Eigen::Map<const Eigen::Vector3d>(gyro.data() + 3 * i);
    samples[i].accel = Eigen::Map<const Eigen::Vector3d>(accel.data() + 3 * i);
  }
  // As ReadEurocImu checks a file (the scales are applied by the caller: accel_unit="g" turns
  // the check off).
  if (read.check_accel_units) CheckAccelNotInG(samples, "imu");
  CheckImuRate(ImuRateHz(samples), "imu['t_ns']");  // as the file readers do
  return samples;
}

namespace {

// The increasing times t_ns and the poses T_w_s (one per time) of the dict `name`, whose keys
// are `keys` (for the message when one is missing).
struct TimedPoses {
  std::vector<int64_t> t_ns;
  std::vector<SE3d> T_w_s;
};

TimedPoses TimedPosesItems(py::handle dict, const std::string& name, const std::string& keys) {
  TimedPoses poses;
  poses.t_ns =
      TimesNs(RequiredItem(dict, name, "t_ns", keys), name + "['t_ns']", /*increasing=*/true);
  poses.T_w_s = PosesFromArray(RequiredItem(dict, name, "T_w_s", keys), name + "['T_w_s']");
  if (poses.T_w_s.size() != poses.t_ns.size()) {
    throw py::value_error(name + "['T_w_s']: expected shape (" + std::to_string(poses.t_ns.size()) +
                          ", 4, 4) to match " + name + "['t_ns'], got " +
                          std::to_string(poses.T_w_s.size()) + " poses");
  }
  return poses;
}

}  // namespace

std::vector<StampedPose> StampedPoses(py::handle poses, const std::string& name) {
  if (const std::optional<std::string> path = AsPath(poses)) return ReadPoses(*path);
  const TimedPoses timed = TimedPosesItems(poses, name, "t_ns, T_w_s");
  const std::vector<int64_t>& t_ns = timed.t_ns;
  const std::vector<SE3d>& T_w_s = timed.T_w_s;
  std::vector<StampedPose> stamped(t_ns.size());
  for (size_t i = 0; i < t_ns.size(); ++i) {
    stamped[i].t_ns = t_ns[i];
    stamped[i].p = T_w_s[i].translation();
    stamped[i].q = T_w_s[i].so3().quaternion();
  }
  return stamped;
}

std::vector<Observation> Observations(py::handle observations) {
  if (const std::optional<std::string> path = AsPath(observations)) {
    return ReadObservationsCsv(*path);
  }
  const std::string name = "observations";
  const std::string keys = "t_ns, cam_id, point_id, uv";
  const std::vector<int64_t> t_ns = TimesNs(
      RequiredItem(observations, name, "t_ns", keys), "observations['t_ns']", /*increasing=*/false);
  const auto n = static_cast<py::ssize_t>(t_ns.size());
  const std::vector<int64_t> cam_id =
      TimesNs(RequiredItem(observations, name, "cam_id", keys), "observations['cam_id']", false);
  const std::vector<int64_t> point_id = TimesNs(
      RequiredItem(observations, name, "point_id", keys), "observations['point_id']", false);
  if (static_cast<py::ssize_t>(cam_id.size()) != n ||
      static_cast<py::ssize_t>(point_id.size()) != n) {
    throw py::value_error("observations: t_ns, cam_id and point_id differ in length");
  }
  const auto uv =
      DoubleArray(RequiredItem(observations, name, "uv", keys), "observations['uv']", {n, 2});
  std::vector<Observation> result(t_ns.size());
  for (py::ssize_t i = 0; i < n; ++i) {
    if (cam_id[i] < 0 || cam_id[i] > 1000) {
      throw py::value_error("observations['cam_id']: expected 0 to 1000, got " +
                            std::to_string(cam_id[i]) + " at row " + std::to_string(i));
    }
    result[i].t_ns = t_ns[i];
    result[i].cam_id = static_cast<int>(cam_id[i]);
    result[i].point_id = point_id[i];
    result[i].uv = Eigen::Map<const Eigen::Vector2d>(uv.data() + 2 * i);
  }
  return result;
}

py::dict ObservationsDict(const std::vector<Observation>& observations) {
  const auto n = static_cast<py::ssize_t>(observations.size());
  py::array_t<int64_t> t_ns(n), cam_id(n), point_id(n);
  py::array_t<double> uv({n, py::ssize_t{2}});
  for (py::ssize_t i = 0; i < n; ++i) {
    t_ns.mutable_data()[i] = observations[i].t_ns;
    cam_id.mutable_data()[i] = observations[i].cam_id;
    point_id.mutable_data()[i] = observations[i].point_id;
    uv.mutable_data()[2 * i] = observations[i].uv.x();
    uv.mutable_data()[2 * i + 1] = observations[i].uv.y();
  }
  py::dict dict;
  dict["t_ns"] = t_ns;
  dict["cam_id"] = cam_id;
  dict["point_id"] = point_id;
  dict["uv"] = uv;
  return dict;
}

py::array_t<int64_t> TimesArray(const std::vector<int64_t>& t_ns) {
  py::array_t<int64_t> array(static_cast<py::ssize_t>(t_ns.size()));
  std::copy(t_ns.begin(), t_ns.end(), array.mutable_data());
  return array;
}

py::array_t<double> Vector3Array(const std::vector<Eigen::Vector3d>& rows) {
  py::array_t<double> array({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
  double* data = array.mutable_data();
  for (size_t i = 0; i < rows.size(); ++i) Eigen::Map<Eigen::Vector3d>(data + 3 * i) = rows[i];
  return array;
}

py::array_t<double> PoseArray(const std::vector<SE3d>& poses) {
  py::array_t<double> array(
      {static_cast<py::ssize_t>(poses.size()), py::ssize_t{4}, py::ssize_t{4}});
  double* data = array.mutable_data();
  for (size_t i = 0; i < poses.size(); ++i) {
    // numpy is row-major: map the block as a row-major 4x4.
    Eigen::Map<Eigen::Matrix<double, 4, 4, Eigen::RowMajor>>(data + 16 * i) = poses[i].matrix();
  }
  return array;
}

py::dict GroundTruthDict(const std::vector<GroundTruthState>& truth) {
  std::vector<SE3d> T_w_s;
  for (const GroundTruthState& s : truth) {
    T_w_s.emplace_back(SO3d::FromQuaternion(s.q_w_s), s.p_w_s);
  }
  py::dict dict;
  dict["t_ns"] = TimeColumn(truth);
  dict["T_w_s"] = PoseArray(T_w_s);
  dict["v_w"] = Vector3Column(truth, [](const auto& s) { return s.v_w; });
  dict["gyro_bias"] = Vector3Column(truth, [](const auto& s) { return s.gyro_bias; });
  dict["accel_bias"] = Vector3Column(truth, [](const auto& s) { return s.accel_bias; });
  return dict;
}

std::vector<GroundTruthState> GroundTruthStates(py::handle truth, const std::string& name) {
  if (const std::optional<std::string> path = AsPath(truth)) return ReadEurocGroundTruth(*path);
  const std::string keys = "t_ns, T_w_s, v_w, gyro_bias, accel_bias";
  const TimedPoses timed = TimedPosesItems(truth, name, keys);
  const std::vector<int64_t>& t_ns = timed.t_ns;
  const std::vector<SE3d>& T_w_s = timed.T_w_s;
  const auto n = static_cast<py::ssize_t>(t_ns.size());
  std::vector<GroundTruthState> states(t_ns.size());
  const char* const columns[] = {"v_w", "gyro_bias", "accel_bias"};
  Eigen::Vector3d GroundTruthState::*fields[] = {
      &GroundTruthState::v_w, &GroundTruthState::gyro_bias, &GroundTruthState::accel_bias};
  for (int c = 0; c < 3; ++c) {
    const auto values = DoubleArray(
        RequiredItem(truth, name, columns[c], keys), name + "['" + columns[c] + "']", {n, 3});
    for (py::ssize_t i = 0; i < n; ++i) {
      states[i].*fields[c] = Eigen::Map<const Eigen::Vector3d>(values.data() + 3 * i);
    }
  }
  for (py::ssize_t i = 0; i < n; ++i) {
    states[i].t_ns = t_ns[i];
    states[i].p_w_s = T_w_s[i].translation();
    states[i].q_w_s = T_w_s[i].so3().quaternion();
  }
  return states;
}

}  // namespace python
}  // namespace splinecal
