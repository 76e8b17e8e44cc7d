// A camera rig as Kalibr describes it in camchain.yaml / camchain-imucam.yaml (docs/conventions.md
// "Camera, time offset, rolling shutter"): per camera the intrinsics and distortion
// (camera/camera_model.h), the image size, the extrinsic T_cam_imu, the camera-IMU time offset
// and the rolling-shutter line delay.
//
//   T_cam_imu      maps IMU-frame points into the camera frame: p_c = T_cam_imu * p_s.
//   time_offset_s  [s]   t_imu = t_cam + time_offset_s (Kalibr's key for it: timeshift_cam_imu).
//   line_delay_s   [s]   image row r of a frame stamped t_frame (camera clock) is exposed at
//                        t_frame + r * line_delay; 0 is a global shutter.
//
// Reading and writing the YAML is io/camchain_yaml.h. CheckCameraIds refuses observations
// (camera/observations.h) of a camera the camchain lacks.
#ifndef SPLINECAL_CAMERA_CAMCHAIN_H_
#define SPLINECAL_CAMERA_CAMCHAIN_H_

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

struct CameraCalibration {
  Camera camera;
  SE3d T_cam_imu;  // identity when the file has none
  double time_offset_s = 0.0;
  double line_delay_s = 0.0;
  std::string rostopic;  // kept from the input, written back when not empty
  // Camera n-1 into camera n (Kalibr's T_cn_cnm1), when the file has it (cam1 onwards): the
  // rig's camera-to-camera poses from a camera calibration (`splinecal intrinsics`).
  std::optional<SE3d> T_cn_cnm1;
};

// cam0, cam1, ... in order.
using Camchain = std::vector<CameraCalibration>;

// Kalibr's order of a camera's parameters, as indices into the intrinsics layout of
// camera/camera_model.h: the `intrinsics` (pinhole [fu fv pu pv], omni [xi fu fv pu pv], eucm
// [alpha beta fu fv pu pv], ds [xi alpha fu fv pu pv]) and the `distortion_coeffs` (radtan k1 k2
// p1 p2, plus OpenCV's k3 when it is estimated or not 0; equidistant k1..k4; fov w; none: none).
// camchain.yaml, result.yaml and the reports all write parameters in this order.
std::vector<int> KalibrIntrinsicsOrder(const Camera& camera);
std::vector<int> KalibrDistortionOrder(const Camera& camera);

// The first observation whose cam_id names no camera of `camchain` (negative, or not below its
// size); nullptr when every observation has its camera.
const Observation* FindObservationWithoutCamera(const std::vector<Observation>& observations,
                                                const Camchain& camchain);

// Throws splinecal::Error naming observations_path for the first observation whose camera is not
// in `camchain` (read from camchain_path): a cam_id beyond it means the camchain of another rig
// or a column mix-up. One line: "cam_id N (frame t_ns T) has no camera in CAMCHAIN, which
// describes K camera(s): wrong camchain or cam_id column".
void CheckCameraIds(const std::vector<Observation>& observations,
                    const Camchain& camchain,
                    const std::string& observations_path,
                    const std::string& camchain_path);

}  // namespace splinecal

#endif  // SPLINECAL_CAMERA_CAMCHAIN_H_
