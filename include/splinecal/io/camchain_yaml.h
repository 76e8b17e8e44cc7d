// Kalibr's camchain.yaml / camchain-imucam.yaml (docs/conventions.md "File formats"), read with the
// one YAML layer (io/yaml_document.h: OpenCV's %YAML:1.0 first line accepted, errors name the
// file and the line) and written with io/yaml_writer.h.
//
// Per camera camN (cam0, cam1, ... consecutive):
//   camera_model       pinhole | omni | eucm | ds (camera/camera_model.h)
//   intrinsics         Kalibr's order per camera model ([px] for fu fv pu pv):
//                        pinhole [fu, fv, pu, pv]; omni [xi, fu, fv, pu, pv];
//                        eucm [alpha, beta, fu, fv, pu, pv]; ds [xi, alpha, fu, fv, pu, pv]
//   distortion_model   none | radtan | equidistant | fov (optional: none); the pairs of
//                      camera/camera_model.h only (pinhole: all four; omni: none, radtan;
//                      eucm, ds: none)
//   distortion_coeffs  radtan [k1, k2, p1, p2] or [k1, k2, p1, p2, k3] (OpenCV's order; 5 sets
//                      Camera::radtan_k3); equidistant [k1, k2, k3, k4]; fov [w] [rad];
//                      none [] (optional; four zeros accepted)
//   resolution         [width, height]                                   [px]
//   T_cam_imu          4x4, list of rows (optional: identity)
//   timeshift_cam_imu  [s] (optional: 0), CameraCalibration::time_offset_s
//   line_delay         [s] per image row (optional: 0, a global shutter)
//   rostopic           (optional, kept)
//   splinecal_covariance  (written when CamchainYamlText is given one with a matrix; not read,
//                      and Kalibr's readers ignore it) parameters: [names], matrix: rows,
//                      block_seconds (camera/parameter_covariance.h)
//   T_cn_cnm1          cam1 onwards: camera n-1 into camera n, 4x4. Read into
//                      CameraCalibration::T_cn_cnm1 (calibrate holds a rig at it on request;
//                      otherwise T_cam_imu is
//                      what splinecal uses). Written: the one the T_cam_imu imply,
//                      T_cn_imu * T_cnm1_imu^-1, so that a stereo extrinsic read from the output
//                      agrees with the estimated T_cam_imu.
// cam_overlaps is ignored.
#ifndef SPLINECAL_IO_CAMCHAIN_YAML_H_
#define SPLINECAL_IO_CAMCHAIN_YAML_H_

#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/parameter_covariance.h"

namespace splinecal {

// Throws splinecal::Error (file:line: what is wrong) for a missing cam0, a missing or invalid
// key, an unsupported camera or distortion model (or pair), a wrong number of intrinsics or
// coefficients, parameters outside their model's domain (Camera::IsValid: fu, fv <= 0, eucm or
// ds alpha outside [0, 1], ...), a non-positive resolution, a T_cam_imu that is not a rigid
// transform, a negative line delay.
Camchain ReadCamchainYaml(const std::string& path);

// cam0's T_cam_imu and timeshift_cam_imu alone (identity and 0 when absent; the camera model is
// left at its default), checked as ReadCamchainYaml checks them: for a command that needs no
// intrinsics (align).
CameraCalibration ReadCam0Extrinsics(const std::string& path);

// The YAML text of `camchain` with every key above but cam_overlaps (Kalibr's
// camchain-imucam.yaml layout; numbers with 17 significant digits so that it reads back exactly).
// radtan writes 5 coefficients when k3 is estimated (radtan_k3) or not zero, else 4.
// kCamerasOnly: Kalibr's camchain.yaml of a camera calibration (`splinecal intrinsics`): the
// camera keys and T_cn_cnm1 from CameraCalibration::T_cn_cnm1 (required from cam1 on), no
// T_cam_imu, timeshift_cam_imu or line_delay.
enum class CamchainKeys { kWithImu, kCamerasOnly };
// covariances: empty, or one per camera (an empty matrix: none written).
std::string CamchainYamlText(const Camchain& camchain,
                             CamchainKeys keys = CamchainKeys::kWithImu,
                             const std::vector<ParameterCovariance>& covariances = {});

// The splinecal_covariance map of one camera (also under each camera of intrinsics' result.yaml).
class YamlWriter;
void WriteParameterCovariance(const ParameterCovariance& covariance, YamlWriter* yaml);

}  // namespace splinecal

#endif  // SPLINECAL_IO_CAMCHAIN_YAML_H_
