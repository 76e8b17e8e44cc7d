// numpy in and out for the Python module: every argument is checked here before it reaches the
// library, so that a wrong shape, dtype, NaN or time order is a ValueError naming the argument
// (`imu['t_ns']: timestamps not increasing at row 5 ...`), never a crash. Time is int64
// nanoseconds only: float seconds would round epoch timestamps (docs/conventions.md, "Time").
#ifndef SPLINECAL_PYTHON_NUMPY_IO_H_
#define SPLINECAL_PYTHON_NUMPY_IO_H_

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/camera/observations.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/se3.h"

namespace splinecal {
namespace python {

namespace py = pybind11;

// The path of a str or os.PathLike argument; nullopt for anything else.
std::optional<std::string> AsPath(py::handle object);

// A path argument (str or os.PathLike), or a ValueError naming it.
std::string PathArgument(py::handle object, const std::string& name);

// Scalar arguments: positive (or >= 0) and finite, or a ValueError naming them.
double PositiveArgument(double value, const std::string& name);
double NonNegativeArgument(double value, const std::string& name);

// A list argument as the command's comma-separated flag takes it ("0,2", "euler,rk4"): a str is
// passed on as it is, a sequence of str or int is joined with commas; TypeError otherwise.
std::string CommaListArgument(py::handle object, const std::string& name);

// The entries of a comma-separated `text` of argument `name` (e.g. bag topics); ValueError
// "<name>: an empty <entry>" for an empty one.
std::vector<std::string> SplitCommaList(const std::string& text,
                                        const std::string& name,
                                        const std::string& entry);

// A 3-vector argument (any sequence of three finite numbers).
Eigen::Vector3d Vector3Argument(py::handle object, const std::string& name);

// `object` as a C-contiguous float64 array of `shape` (-1: any length, at least 1), every value
// finite. Any real dtype is accepted (int, float); bool, complex, object and strings are not.
py::array_t<double> DoubleArray(py::handle object,
                                const std::string& name,
                                const std::vector<py::ssize_t>& shape);

// Timestamps [ns], shape (n,) with n >= 1, an integer dtype; strictly increasing if asked.
std::vector<int64_t> TimesNs(py::handle object, const std::string& name, bool increasing);

// A rotation check for a pose given as a 4x4 matrix: R orthonormal (1e-6) with det +1 and the
// bottom row (0, 0, 0, 1); `name` names the pose in the error.
SE3d PoseFromMatrix(const Eigen::Matrix4d& T, const std::string& name);

// Poses of shape (n, 4, 4), each checked by PoseFromMatrix.
std::vector<SE3d> PosesFromArray(py::handle object, const std::string& name);

// A dict's item, or a ValueError naming the argument and the keys it needs.
py::object RequiredItem(py::handle dict,
                        const std::string& name,
                        const char* key,
                        const std::string& keys);

// IMU samples: a path (EuRoC imu0/data.csv, read and checked as the command line does with
// `read`), or a dict {"t_ns": int64 (n,), "gyro": (n, 3) [rad/s], "accel": (n, 3) [m/s^2]}.
std::vector<ImuSample> ImuSamples(py::handle imu, const ImuReadOptions& read);

// Poses: a path (EuRoC ground truth or TUM, as the command line reads them) or a dict
// {"t_ns": int64 (n,), "T_w_s": (n, 4, 4)}.
std::vector<StampedPose> StampedPoses(py::handle poses, const std::string& name);

// Camera observations: a path (observations.csv) or a dict {"t_ns": int64 (n,), "cam_id": int
// (n,), "point_id": int (n,), "uv": (n, 2) [px]} (t_ns: frame times, any order).
std::vector<Observation> Observations(py::handle observations);
py::dict ObservationsDict(const std::vector<Observation>& observations);

// Ground truth states: a path (EuRoC state_groundtruth_estimate0/data.csv) or a dict
// {"t_ns", "T_w_s" (n, 4, 4), "v_w", "gyro_bias", "accel_bias" (n, 3)}, as GroundTruthDict
// returns them (the ground truth of splinecal.simulate and splinecal.align go straight in).
std::vector<GroundTruthState> GroundTruthStates(py::handle truth, const std::string& name);
py::dict GroundTruthDict(const std::vector<GroundTruthState>& truth);

// Output arrays.
py::array_t<int64_t> TimesArray(const std::vector<int64_t>& t_ns);
py::array_t<double> Vector3Array(const std::vector<Eigen::Vector3d>& rows);
py::array_t<double> PoseArray(const std::vector<SE3d>& poses);  // (n, 4, 4)

// Columns of a table of structs: the rows' t_ns (n,), and field(row) as an (n, 3) array.
template <typename Row>
py::array_t<int64_t> TimeColumn(const std::vector<Row>& rows) {
  py::array_t<int64_t> array(static_cast<py::ssize_t>(rows.size()));
  for (size_t i = 0; i < rows.size(); ++i) array.mutable_data()[i] = rows[i].t_ns;
  return array;
}
template <typename Row, typename Field>
py::array_t<double> Vector3Column(const std::vector<Row>& rows, Field field) {
  py::array_t<double> array({static_cast<py::ssize_t>(rows.size()), py::ssize_t{3}});
  double* data = array.mutable_data();
  for (size_t i = 0; i < rows.size(); ++i) {
    Eigen::Map<Eigen::Vector3d>(data + 3 * i) = field(rows[i]);
  }
  return array;
}

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_NUMPY_IO_H_
