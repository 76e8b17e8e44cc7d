// calibrate's camera choices made before Calibrate() (calib/calibrate.h): the selection of
// cameras (--cameras), the held camera chain (--hold-camera-chain) and the check that every
// selected camera has observations (a camera without any leaves the problem singular: every
// standard deviation NaN). The command line and the Python module both call
// SelectCalibrationCameras, so that they choose and refuse the same way.
#ifndef SPLINECAL_CALIB_CAMERA_SELECTION_H_
#define SPLINECAL_CALIB_CAMERA_SELECTION_H_

#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"

namespace splinecal {

// Parses --cameras "0,2" (camchain indices, increasing, no repeats) against a camchain of
// num_cameras cameras; empty text selects all. Throws splinecal::Error naming the flag.
std::vector<int> ParseCameraSelection(const std::string& text, int num_cameras);

// Keeps the selected cameras, renumbered 0.. in the order given (Kalibr's camchain keys must be
// consecutive: input camera selection[k] becomes camk), and their observations with cam_id
// renumbered the same way; drops the others' observations.
void SelectCameras(const std::vector<int>& selection,
                   Camchain* camchain,
                   std::vector<Observation>* observations);

// Throws splinecal::Error when a camera of the camchain has no observation, naming it (by its
// input index, input_ids[k] for camera k) and observations_path, and the --cameras value that
// leaves it out.
void CheckEveryCameraObserved(const std::vector<Observation>& observations,
                              const Camchain& camchain,
                              const std::vector<int>& input_ids,
                              const std::string& observations_path);

// T_cn_c0 of every selected camera (selection: camchain indices; empty: all) from the camchain's
// T_cn_cnm1 chain, relative to the first selected camera: CalibrateOptions::camera_chain_T_cn_c0
// for --hold-camera-chain. Throws splinecal::Error naming camchain_path when a camera after the
// first has no T_cn_cnm1.
std::vector<SE3d> HeldCameraChain(const Camchain& camchain,
                                  const std::vector<int>& selection,
                                  const std::string& camchain_path);

// Everything calibrate does to its camchain and observations before Calibrate(): checks every
// cam_id against the camchain (CheckCameraIds), parses `cameras` (ParseCameraSelection), fills
// options->camera_chain_T_cn_c0 when hold_camera_chain, keeps the selected cameras
// (SelectCameras) and checks that each has observations (CheckEveryCameraObserved).
void SelectCalibrationCameras(const std::string& cameras,
                              bool hold_camera_chain,
                              const std::string& camchain_path,
                              const std::string& observations_path,
                              Camchain* camchain,
                              std::vector<Observation>* observations,
                              CalibrateOptions* options);

}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CAMERA_SELECTION_H_
