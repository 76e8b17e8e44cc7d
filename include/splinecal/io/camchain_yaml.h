// Kalibr's camchain.yaml / camchain-imucam.yaml (CONVENTIONS.md "File formats"), read with the
// one YAML layer (io/yaml_document.h: OpenCV's %YAML:1.0 first line accepted, errors name the
// file and the line) and written with io/yaml_writer.h.
//
// Per camera camN (cam0, cam1, ... consecutive):
//   camera_model       pinhole (the only model; others are refused by name)
//   intrinsics         [fu, fv, pu, pv]                                  [px]
//   distortion_model   radtan | equidistant | none
//   distortion_coeffs  radtan [k1, k2, p1, p2]; equidistant [k1, k2, k3, k4]; none [] (optional)
//   resolution         [width, height]                                   [px]
//   T_cam_imu          4x4, list of rows (optional: identity)
//   timeshift_cam_imu  [s] (optional: 0), CameraCalibration::time_offset_s
//   line_delay         [s] per image row (optional: 0, a global shutter)
//   rostopic           (optional, kept)
//   T_cn_cnm1          cam1 onwards: camera n-1 into camera n, 4x4. Read: ignored (T_cam_imu is
//                      what splinecal uses). Written: the one the T_cam_imu imply,
//                      T_cn_imu * T_cnm1_imu^-1, so that a stereo extrinsic read from the output
//                      agrees with the estimated T_cam_imu.
// cam_overlaps is ignored.
#ifndef SPLINECAL_IO_CAMCHAIN_YAML_H_
#define SPLINECAL_IO_CAMCHAIN_YAML_H_

#include <string>

#include "splinecal/camera/camchain.h"

namespace splinecal {

// Throws splinecal::Error (file:line: what is wrong) for a missing cam0, a missing or invalid
// key, an unsupported camera or distortion model, a wrong number of coefficients, non-positive
// focal lengths or resolution, a T_cam_imu that is not a rigid transform, a negative line
// delay.
Camchain ReadCamchainYaml(const std::string& path);

// cam0's T_cam_imu and timeshift_cam_imu alone (identity and 0 when absent; the camera model is
// left at its default), checked as ReadCamchainYaml checks them: for a command that needs no
// intrinsics (align).
CameraCalibration ReadCam0Extrinsics(const std::string& path);

// The YAML text of `camchain` with every key above but cam_overlaps (Kalibr's
// camchain-imucam.yaml layout; numbers with 17 significant digits so that it reads back exactly).
std::string CamchainYamlText(const Camchain& camchain);

}  // namespace splinecal

#endif  // SPLINECAL_IO_CAMCHAIN_YAML_H_
