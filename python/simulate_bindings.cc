// splinecal.simulate: `splinecal simulate` (sim/simulation_result.h, RunSimulation) returning
// its result.yaml as a dict plus the simulated data as arrays.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cmath>
#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/sim/simulation_result.h"
#include "splinecal/sim/trajectories.h"

namespace splinecal {
namespace python {

namespace {

// `splinecal simulate`'s limit: 2e7 samples is 27 hours at 200 Hz (~200 bytes each in memory).
constexpr double kMaxSamples = 2e7;

py::dict ImuDict(const std::vector<ImuSample>& imu) {
  py::dict dict;
  dict["t_ns"] = TimeColumn(imu);
  dict["gyro"] = Vector3Column(imu, [](const auto& s) { return s.gyro; });
  dict["accel"] = Vector3Column(imu, [](const auto& s) { return s.accel; });
  return dict;
}

py::dict Simulate(const std::string& trajectory_name,
                  py::object trajectory_file,
                  py::object duration,
                  double imu_rate,
                  double knot_spacing,
                  int64_t seed,
                  double gravity,
                  py::object imu_yaml,
                  double gyroscope_noise_density,
                  double gyroscope_random_walk,
                  double accelerometer_noise_density,
                  double accelerometer_random_walk,
                  bool noise_free,
                  py::object camchain,
                  py::object target,
                  int landmarks,
                  double camera_rate,
                  double pixel_noise,
                  py::handle gyro_bias,
                  py::handle accel_bias,
                  py::object imu_intrinsics,
                  py::handle out) {
  SimulationRun run;
  SimulationOptions& options = run.options;
  options.imu_rate_hz = PositiveArgument(imu_rate, "imu_rate");
  if (!(knot_spacing >= 0.001) || !(knot_spacing <= 1e9)) {
    throw py::value_error("knot_spacing: must be 0.001 s to 1e9 s, got " +
                          std::to_string(knot_spacing));
  }
  run.knot_spacing_s = knot_spacing;
  const int64_t knot_spacing_ns = std::llround(knot_spacing * 1e9);
  if (!imu_yaml.is_none()) {
    options.noise = ReadImuYaml(PathArgument(imu_yaml, "imu_yaml"));
  } else {
    options.noise.gyroscope_noise_density =
        NonNegativeArgument(gyroscope_noise_density, "gyroscope_noise_density");
    options.noise.gyroscope_random_walk =
        NonNegativeArgument(gyroscope_random_walk, "gyroscope_random_walk");
    options.noise.accelerometer_noise_density =
        NonNegativeArgument(accelerometer_noise_density, "accelerometer_noise_density");
    options.noise.accelerometer_random_walk =
        NonNegativeArgument(accelerometer_random_walk, "accelerometer_random_walk");
  }
  options.noise.update_rate_hz = options.imu_rate_hz;
  options.noise_free = noise_free;
  options.gyro_bias = Vector3Argument(gyro_bias, "gyro_bias");
  options.accel_bias = Vector3Argument(accel_bias, "accel_bias");
  options.seed = static_cast<uint64_t>(seed);
  options.gravity_m_s2 = PositiveArgument(gravity, "gravity");
  if (!imu_intrinsics.is_none()) {
    // As `splinecal simulate --imu-intrinsics`: imu0 is the spline's body, imu1.. further IMUs.
    const std::vector<ImuCalibration> imus =
        ReadImuModelsYaml(PathArgument(imu_intrinsics, "imu_intrinsics"));
    options.imu = imus.front();
    run.more_imus.assign(imus.begin() + 1, imus.end());
  }

  SimulationTrajectory trajectory;
  trajectory.name = trajectory_name;
  trajectory.seed = options.seed;
  CameraSimulationOptions& camera_options = run.camera_options;
  if (!camchain.is_none()) {
    run.camchain = ReadCamchainYaml(PathArgument(camchain, "camchain"));
    camera_options.camera_rate_hz = PositiveArgument(camera_rate, "camera_rate");
    camera_options.pixel_noise_px = NonNegativeArgument(pixel_noise, "pixel_noise");
    camera_options.seed = options.seed + 100;  // as `splinecal simulate`
    if (landmarks < 0 || landmarks > 1000000) {
      throw py::value_error("landmarks: expected 0 to 1000000, got " + std::to_string(landmarks));
    }
    camera_options.num_landmarks = landmarks;
    if (!target.is_none()) {
      camera_options.has_target = true;
      camera_options.target = ReadTargetYaml(PathArgument(target, "target"));
      trajectory.target_centre_w = TargetCentre(camera_options.target, camera_options.T_w_t);
    }
    if (!camera_options.has_target && landmarks == 0) {
      throw py::value_error("camchain: needs target and/or landmarks: nothing to observe");
    }
    trajectory.T_cam_imu = run.camchain.front().T_cam_imu;
  } else if (!target.is_none() || landmarks != 0) {
    throw py::value_error("target, landmarks: need camchain (the cameras that observe them)");
  }

  // The time range, as `splinecal simulate` chooses it.
  const double duration_s =
      duration.is_none() ? 20.0 : PositiveArgument(duration.cast<double>(), "duration");
  const int64_t duration_ns = std::llround(duration_s * 1e9);
  if (!trajectory_file.is_none()) {
    trajectory.recorded_source = PathArgument(trajectory_file, "trajectory_file");
    trajectory.recorded_poses = ReadPoses(trajectory.recorded_source);
    run.start_ns = trajectory.recorded_poses.front().t_ns;
    run.end_ns = trajectory.recorded_poses.back().t_ns;
    if (!duration.is_none()) {
      if (run.start_ns + duration_ns > run.end_ns) {
        throw py::value_error("duration: longer than the trajectory_file");
      }
      run.end_ns = run.start_ns + duration_ns;
    }
  } else {
    if (trajectory_name == "calibration") {
      if (run.camchain.empty()) throw py::value_error("trajectory 'calibration' needs camchain");
      run.start_ns = 1'000'000'000;
    } else {
      MakeTrajectory(trajectory_name, options.seed);  // refuses an unknown name
      run.start_ns = knot_spacing_ns;                 // the first knot at t = 0, the IMU from t_1
    }
    run.end_ns = run.start_ns + duration_ns;
  }
  if ((run.end_ns - run.start_ns) * 1e-9 * options.imu_rate_hz > kMaxSamples) {
    throw py::value_error("duration: more than 2e7 IMU samples: shorten it");
  }

  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  RunWithoutGil([&] {
    RunSimulation(trajectory, PoseFitOptions(), &run);
    return 0;
  });
  py::dict result = FinishOutputs(output.get(), SimulationOutputFiles(run));
  result["imu"] = ImuDict(run.imu);
  for (size_t k = 0; k < run.more_imu.size(); ++k) {
    result[("imu" + std::to_string(k + 1)).c_str()] = ImuDict(run.more_imu[k]);
  }
  result["ground_truth"] = GroundTruthDict(run.truth);
  result["se3_spline"] = py::cast(run.spline.fit.MakeSpline());
  if (!run.camchain.empty()) result["observations"] = ObservationsDict(run.cameras.observations);
  return result;
}

}  // namespace

void BindSimulate(py::module_& m) {
  const ImuNoise adis;  // the defaults: EuRoC's ADIS16448
  DefCommand(m,
             "simulate",
             &Simulate,
             R"(Simulated IMU data (and camera observations with camchain), as `splinecal simulate`
with the same keyword names as its flags (duration None: 20 s, or the whole trajectory_file).
Returns result.yaml's keys plus imu {t_ns, gyro, accel}, ground_truth {t_ns, T_w_s, v_w,
gyro_bias, accel_bias}, se3_spline (SE3Spline) and with camchain observations {t_ns, cam_id,
point_id, uv}; with imu_intrinsics (Kalibr's imu-*.yaml path: IMU models and further IMUs,
docs/imu_models.md) also imu1, imu2, ... {t_ns, gyro, accel}. out: a folder to write the
command's files to (mav0/imu0/data.csv, ...).)",
             py::kw_only(),
             py::arg("trajectory") = "vio_course",
             py::arg("trajectory_file") = py::none(),
             py::arg("duration") = py::none(),
             py::arg("imu_rate") = 200.0,
             py::arg("knot_spacing") = 0.05,
             py::arg("seed") = 1,
             py::arg("gravity") = kDefaultGravity,
             py::arg("imu_yaml") = py::none(),
             py::arg("gyroscope_noise_density") = adis.gyroscope_noise_density,
             py::arg("gyroscope_random_walk") = adis.gyroscope_random_walk,
             py::arg("accelerometer_noise_density") = adis.accelerometer_noise_density,
             py::arg("accelerometer_random_walk") = adis.accelerometer_random_walk,
             py::arg("noise_free") = false,
             py::arg("camchain") = py::none(),
             py::arg("target") = py::none(),
             py::arg("landmarks") = 0,
             py::arg("camera_rate") = 20.0,
             py::arg("pixel_noise") = 0.5,
             py::arg("gyro_bias") = std::vector<double>{0.0, 0.0, 0.0},
             py::arg("accel_bias") = std::vector<double>{0.0, 0.0, 0.0},
             py::arg("imu_intrinsics") = py::none());
}

}  // namespace python
}  // namespace splinecal
