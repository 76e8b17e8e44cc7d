// The cameras `splinecal intrinsics` calibrates, from its --models, --resolution and --camchain
// (docs/intrinsics.md), and the check of observations.csv's cam_ids against them. The command
// line and the Python module both call these, so that they read and refuse the same way; the
// messages name the command's flags.
#ifndef SPLINECAL_INTRINSICS_CAMERA_SPECS_H_
#define SPLINECAL_INTRINSICS_CAMERA_SPECS_H_

#include <string>
#include <vector>

#include "splinecal/camera/camchain.h"
#include "splinecal/camera/observations.h"
#include "splinecal/intrinsics/calibrate_intrinsics.h"

namespace splinecal {

// One spec per entry of `models` (comma-separated Kalibr model names, cam0 first). The image
// sizes come from `resolution` (WxH, one for all or one per model) or from the camchain read
// from camchain_path (exactly one of the two non-empty); a camchain camera of the same model
// gives its values as the starting point. `cameras` ("0,2"; empty: all) selects input cameras
// (the camchain's, else the cam_ids of `observations`): `models` then names the selected ones,
// which become cam0, cam1, ... in this order, and `observations` keeps only theirs, renumbered.
// Throws splinecal::Error for an unknown model, a bad size, a count mismatch or both/neither of
// resolution and camchain.
std::vector<IntrinsicsCameraSpec> IntrinsicsCameraSpecs(const std::string& models,
                                                        const std::string& resolution,
                                                        const std::string& camchain_path,
                                                        const std::string& cameras,
                                                        std::vector<Observation>* observations);

// Throws splinecal::Error naming observations_path when a cam_id has no model.
void CheckIntrinsicsCameraIds(const std::vector<Observation>& observations,
                              size_t num_models,
                              const std::string& observations_path);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_CAMERA_SPECS_H_
