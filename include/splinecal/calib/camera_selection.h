// calibrate's camera choices made before Calibrate() (calib/calibrate.h): the selection of
// cameras (--cameras), the camera chain and covariances of the selected cameras (--camera-chain,
// the camchain's splinecal_covariance) and the check that every
// selected camera has observations (a camera without any leaves the problem singular: every
// standard deviation NaN). The command line and the Python module both call
// SelectCalibrationCameras, so that they choose and refuse the same way.
#ifndef SPLINECAL_CALIB_CAMERA_SELECTION_H_
#define SPLINECAL_CALIB_CAMERA_SELECTION_H_

#include <optional>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/io/camchain_yaml_covariance.h"

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
// T_cn_cnm1 chain, relative to the first selected camera: CalibrateOptions::camera_chain_T_cn_c0.
// Throws splinecal::Error naming camchain_path and `why` (the flag that needs the chain) when a
// camera after the first has no T_cn_cnm1.
std::vector<SE3d> HeldCameraChain(const Camchain& camchain,
                                  const std::vector<int>& selection,
                                  const std::string& camchain_path,
                                  const std::string& why);

// The covariances of the selected cameras, renumbered like the camchain: a camera whose
// predecessor in the selection is not its predecessor in the file loses its T_cn_cnm1 rows
// (they are of the file's T_cn_cnm1).
std::vector<std::optional<CameraCovariance>> SelectCovariances(
    const std::vector<std::optional<CameraCovariance>>& all, const std::vector<int>& selection);

// calibrate's --intrinsics / --camera-chain value: "held", "prior" or "free"; "" gives nullopt
// (CalibrateOptions' default rule). `alias` is a deprecated switch (--estimate-intrinsics,
// --hold-camera-chain) that means alias_mode; set with a contradicting value it is an error.
// Throws splinecal::Error naming the flag.
std::optional<ParameterMode> ParseParameterMode(const std::string& flag,
                                                const std::string& value,
                                                bool alias = false,
                                                ParameterMode alias_mode = ParameterMode::kFree,
                                                const std::string& alias_flag = "");

// calibrate's --target-scale value: "check", "free" or "held". Throws splinecal::Error.
TargetScaleMode ParseTargetScaleMode(const std::string& flag, const std::string& value);

// Everything calibrate does to its camchain and observations before Calibrate(): checks every
// cam_id against the camchain (CheckCameraIds), parses `cameras` (ParseCameraSelection), sets
// options->camchain_covariances from `covariances` (one per camchain camera, or empty), fills
// options->camera_chain_T_cn_c0 when options->camera_chain asks for the chain (held or prior;
// by default when every selected camera after the first has T_cn_cnm1 rows), keeps the selected
// cameras (SelectCameras) and checks that each has observations (CheckEveryCameraObserved).
void SelectCalibrationCameras(const std::string& cameras,
                              const std::string& camchain_path,
                              const std::string& observations_path,
                              const std::vector<std::optional<CameraCovariance>>& covariances,
                              Camchain* camchain,
                              std::vector<Observation>* observations,
                              CalibrateOptions* options);
}  // namespace splinecal

#endif  // SPLINECAL_CALIB_CAMERA_SELECTION_H_
