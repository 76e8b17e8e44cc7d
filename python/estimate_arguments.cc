#include "estimate_arguments.h"

#include "numpy_io.h"
#include "splinecal/io/bag_imu.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace python {

void ApplyEstimateArguments(const EstimateArguments& arguments,
                            SplineModelOptions* model,
                            SolverOptions* solver) {
  // Bounded as the command line bounds it: int64 knot times cannot overflow.
  if (!(arguments.knot_spacing >= 0.0) || !(arguments.knot_spacing <= 1e9)) {
    throw py::value_error("knot_spacing: expected 0 (chosen from the data) to 1e9 s, got " +
                          std::to_string(arguments.knot_spacing));
  }
  model->knot_spacing_s = arguments.knot_spacing;
  model->gravity_m_s2 = PositiveArgument(arguments.gravity, "gravity");
  if (!arguments.imu_yaml.is_none()) {
    model->noise = ReadImuYaml(PathArgument(arguments.imu_yaml, "imu_yaml"));
  }
  if (!ValueNamed(kImuNoiseModeNames, arguments.imu_noise, &model->imu_noise)) {
    throw py::value_error("imu_noise: expected " + JoinNames(kImuNoiseModeNames, ", ") +
                          ", got '" + arguments.imu_noise + "'");
  }
  model->trajectory = TrajectoryArgument(arguments.trajectory);
  if (arguments.threads < 1 || arguments.threads > 256) {
    throw py::value_error("threads: expected 1 to 256, got " + std::to_string(arguments.threads));
  }
  solver->num_threads = arguments.threads;
}

TrajectoryModel TrajectoryArgument(const std::string& name) {
  TrajectoryModel model = TrajectoryModel::kSE3;
  if (!ParseTrajectoryModel(name, &model)) {
    throw py::value_error("trajectory: expected se3 or split, got '" + name + "'");
  }
  return model;
}

std::vector<ImuSample> ImuInUnits(py::handle imu, const EstimateArguments& arguments) {
  return ImuInUnits(imu, arguments.accel_unit, arguments.gyro_unit);
}

std::vector<ImuSample> ImuInUnits(py::handle imu,
                                  const std::string& accel_unit,
                                  const std::string& gyro_unit) {
  ImuReadOptions read = ImuUnitReadOptions(accel_unit, gyro_unit);
  read.yaml_hint =
      "IMU noise densities (Kalibr's imu.yaml) go to imu_yaml; imu takes the IMU samples";
  const bool from_file = AsPath(imu).has_value();
  std::vector<ImuSample> samples = ImuSamples(imu, read);
  if (!from_file) {  // the reader scales what it reads; arrays are scaled here
    for (ImuSample& s : samples) {
      s.gyro *= read.gyro_scale;
      s.accel *= read.accel_scale;
    }
  }
  return samples;
}

std::string ImuYamlPath(const EstimateArguments& arguments) {
  return arguments.imu_yaml.is_none() ? "" : PathArgument(arguments.imu_yaml, "imu_yaml");
}

py::handle RequiredArgument(py::handle value, const std::string& name) {
  if (value.is_none()) throw py::type_error("missing required argument '" + name + "'");
  return value;
}

std::vector<std::string> BagPaths(py::handle bag) {
  if (const std::optional<std::string> path = AsPath(bag)) return {*path};
  std::vector<std::string> paths;
  if (py::isinstance<py::list>(bag) || py::isinstance<py::tuple>(bag)) {
    for (py::handle item : bag) paths.push_back(PathArgument(item, "bag"));
  }
  if (paths.empty()) {
    throw py::value_error("bag: expected a path or a list of paths (one split recording)");
  }
  return paths;
}

namespace {

// The bag's source, nullopt without bag; ValueError unless exactly one of imu and bag is given.
std::optional<BagImuSource> BagSource(py::handle imu, const BagImuArguments& bag) {
  if (imu.is_none() == bag.bag.is_none()) {
    throw py::value_error(
        "imu, bag: give the IMU samples as imu (a EuRoC imu0/data.csv path or arrays) or as bag "
        "(a recording) with imu_topic: exactly one");
  }
  if (bag.bag.is_none()) return std::nullopt;
  BagImuSource source;
  source.paths = BagPaths(bag.bag);
  source.topic = bag.imu_topic;
  if (source.topic.empty()) throw py::value_error("imu_topic: empty");
  source.time = ParseBagTime(bag.bag_time);
  return source;
}

}  // namespace

std::vector<ImuSample> ImuInUnits(py::handle imu,
                                  const BagImuArguments& bag,
                                  const std::string& accel_unit,
                                  const std::string& gyro_unit) {
  const std::optional<BagImuSource> source = BagSource(imu, bag);
  if (!source.has_value()) return ImuInUnits(imu, accel_unit, gyro_unit);
  ImuReadOptions read = ImuUnitReadOptions(accel_unit, gyro_unit);
  return ReadBagImu(*source, read);
}

std::string ImuSourceName(py::handle imu, const BagImuArguments& bag,
                          const std::string& fallback) {
  const std::optional<BagImuSource> source = BagSource(imu, bag);
  if (source.has_value()) return source->Name();
  return AsPath(imu).value_or(fallback);
}

}  // namespace python
}  // namespace splinecal
