// splinecal.align: `splinecal align` (vio/align.h) with every flag as a keyword, returning its
// result.yaml (report/command_outputs.h) as a dict plus the aligned IMU poses as arrays.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <memory>

#include "bindings.h"
#include "command_outputs.h"
#include "estimate_arguments.h"
#include "interruptible.h"
#include "numpy_io.h"
#include "splinecal/error.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/vio/align.h"

namespace splinecal {
namespace python {

namespace {

py::dict AlignFunction(py::handle imu,
                       py::handle camera_poses,
                       py::handle camchain,
                       py::handle imu_yaml,
                       bool estimate_rotation_extrinsic,
                       double gravity,
                       py::handle accel_bias,
                       double camera_position_std,
                       double camera_rotation_std,
                       const std::string& accel_unit,
                       const std::string& gyro_unit,
                       py::handle out) {
  AlignOptions options;
  options.gravity_m_s2 = PositiveArgument(gravity, "gravity");
  options.estimate_rotation_extrinsic = estimate_rotation_extrinsic;
  if (!imu_yaml.is_none()) options.noise = ReadImuYaml(PathArgument(imu_yaml, "imu_yaml"));
  options.accel_bias = Vector3Argument(accel_bias, "accel_bias");
  options.camera_noise.position_std_m =
      PositiveArgument(camera_position_std, "camera_position_std");
  options.camera_noise.rotation_std_rad =
      PositiveArgument(camera_rotation_std, "camera_rotation_std");
  if (!camchain.is_none()) {
    const CameraCalibration cam0 = ReadCam0Extrinsics(PathArgument(camchain, "camchain"));
    options.T_cam_imu = cam0.T_cam_imu;
    options.time_offset_s = cam0.time_offset_s;
  }
  const std::unique_ptr<OutputDir> output = OutputArgument(out);
  const std::vector<ImuSample> samples = ImuInUnits(imu, accel_unit, gyro_unit);
  const std::vector<StampedPose> poses = StampedPoses(camera_poses, "camera_poses");

  const AlignResult result = RunWithoutGil([&] { return Align(samples, poses, options); });
  // As the command: a refused alignment is bad input, with the library's reason.
  if (!result.success) throw Error("alignment refused: " + result.message);
  py::dict dict = FinishOutputs(output.get(), AlignOutputFiles(result, options));
  dict["aligned_poses"] = GroundTruthDict(result.states_w);
  return dict;
}

}  // namespace

void BindAlign(py::module_& m) {
  const AlignOptions defaults;
  DefCommand(
      m,
      "align",
      &AlignFunction,
      R"(Visual-inertial alignment as `splinecal align`, with its flags as keywords. imu: a EuRoC
imu0/data.csv path or {t_ns, gyro, accel}; camera_poses (T_c0_c up to scale): a TUM / EuRoC
ground truth path or {t_ns, T_w_s (n, 4, 4)}; camchain: a Kalibr camchain.yaml path (cam0's
T_cam_imu and timeshift_cam_imu). out: a folder to write result.yaml and aligned_poses.csv to.
Returns result.yaml's keys plus aligned_poses {t_ns, T_w_s, v_w, gyro_bias, accel_bias}, the
IMU poses in the gravity-aligned world (fit's poses, calibrate's initial_poses). A motion that
does not determine scale and gravity raises splinecal.Error ("alignment refused: ...").)",
      py::arg("imu"),
      py::arg("camera_poses"),
      py::kw_only(),
      py::arg("camchain") = py::none(),
      py::arg("imu_yaml") = py::none(),
      py::arg("estimate_rotation_extrinsic") = defaults.estimate_rotation_extrinsic,
      py::arg("gravity") = defaults.gravity_m_s2,
      py::arg("accel_bias") = std::vector<double>{0.0, 0.0, 0.0},
      py::arg("camera_position_std") = defaults.camera_noise.position_std_m,
      py::arg("camera_rotation_std") = defaults.camera_noise.rotation_std_rad,
      py::arg("accel_unit") = "m/s^2",
      py::arg("gyro_unit") = "rad/s");
}

}  // namespace python
}  // namespace splinecal
