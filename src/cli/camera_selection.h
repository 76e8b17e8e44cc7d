// calibrate's camera selection (--cameras) and its check that every camera of the camchain has
// observations (a camera without any leaves the problem singular: every standard deviation NaN).
#ifndef SPLINECAL_SRC_CLI_CAMERA_SELECTION_H_
#define SPLINECAL_SRC_CLI_CAMERA_SELECTION_H_

#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"

namespace splinecal {
namespace cli {

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

}  // namespace cli
}  // namespace splinecal

#endif  // SPLINECAL_SRC_CLI_CAMERA_SELECTION_H_
