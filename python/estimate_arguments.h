// The keyword arguments fit() and calibrate() share, read as their command-line flags are
// (src/cli/common_flags.cc): the spline model (knot_spacing, gravity, imu_yaml, imu_noise,
// trajectory), the IMU's units and the solver's threads.
#ifndef SPLINECAL_PYTHON_ESTIMATE_ARGUMENTS_H_
#define SPLINECAL_PYTHON_ESTIMATE_ARGUMENTS_H_

#include <pybind11/pybind11.h>

#include <string>
#include <vector>

#include "command_outputs.h"
#include "splinecal/estimation/options.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/spline/trajectory_model.h"

namespace splinecal {
namespace python {

struct EstimateArguments {
  double knot_spacing = 0.0;         // [s]; 0: chosen from the IMU data
  double gravity = kDefaultGravity;  // [m/s^2]
  pybind11::object imu_yaml;  // path of a Kalibr imu.yaml, or None (ADIS16448)
  std::string imu_noise = "estimated";
  std::string accel_unit = "m/s^2";
  std::string gyro_unit = "rad/s";
  int threads = 1;
  std::string trajectory = "se3";  // se3 or split (spline/trajectory_model.h)
};

// Fills `model` and `solver` (threads) from the arguments; ValueError for a bad one.
void ApplyEstimateArguments(const EstimateArguments& arguments,
                            SplineModelOptions* model,
                            SolverOptions* solver);

// The trajectory model named `name` (se3 or split); ValueError for another name.
TrajectoryModel TrajectoryArgument(const std::string& name);

// The IMU samples of `imu` (a path or a dict, numpy_io.h) in rad/s and m/s^2.
std::vector<ImuSample> ImuInUnits(pybind11::handle imu, const EstimateArguments& arguments);
// The same for the units named as --accel-unit and --gyro-unit name them (io/imu_units.h).
std::vector<ImuSample> ImuInUnits(pybind11::handle imu,
                                  const std::string& accel_unit,
                                  const std::string& gyro_unit);

// The path of imu_yaml for the report inputs ("" for None).
std::string ImuYamlPath(const EstimateArguments& arguments);

// The bag keywords of the functions that read IMU samples, as the commands' --bag, --imu-topic
// and --bag-time (docs/bags.md, "Commands on a bag"): bag is a path or a list of paths (one
// split recording), None for imu.
struct BagImuArguments {
  pybind11::handle bag;
  std::string imu_topic = "/imu0";
  std::string bag_time = "header";
};

// DefCommand of a command that reads IMU samples from a file or a bag: after `out`, the bag
// keywords with BagImuArguments' defaults (its function's last four parameters).
template <typename... Definition>
void DefImuCommand(pybind11::module_& m, const char* name, const Definition&... definition) {
  const BagImuArguments defaults;
  m.def(name,
        definition...,
        OutArgument(),
        pybind11::arg("bag") = pybind11::none(),
        pybind11::arg("imu_topic") = defaults.imu_topic,
        pybind11::arg("bag_time") = defaults.bag_time);
}

// The samples of `imu` (a path or arrays, as ImuInUnits) or of the bag's topic (ReadBagImu, the
// same checks), in the units named; ValueError unless exactly one of imu and bag is given.
std::vector<ImuSample> ImuInUnits(pybind11::handle imu,
                                  const BagImuArguments& bag,
                                  const std::string& accel_unit,
                                  const std::string& gyro_unit);
// Where the samples come from, for the results: imu's path, "FILE:TOPIC" for a bag, else
// `fallback` (arrays).
std::string ImuSourceName(pybind11::handle imu, const BagImuArguments& bag,
                          const std::string& fallback = "");
// `value`, or TypeError "missing required argument 'name'" for None: the arguments after imu,
// which has a default (None: the samples come from bag), need one too.
pybind11::handle RequiredArgument(pybind11::handle value, const std::string& name);
// The recording of `bag` (a path or a list of paths); ValueError naming bag otherwise.
std::vector<std::string> BagPaths(pybind11::handle bag);

}  // namespace python
}  // namespace splinecal

#endif  // SPLINECAL_PYTHON_ESTIMATE_ARGUMENTS_H_
