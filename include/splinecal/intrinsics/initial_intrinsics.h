// A starting point for a camera's intrinsics from target views alone, for any camera model
// (calib/calibrate_intrinsics.h, step 2).
//
// A homography (Zhang's method) assumes a pinhole: a fisheye or an omnidirectional lens maps
// straight target lines to curves, and its focal length is not where a pinhole fit puts it.
// Instead, every candidate camera of the model itself is tried: focal lengths on a geometric
// grid (fu = fv = f, kFocalSteps values from kMinFocalWidths to kMaxFocalWidths image widths)
// times the model's shape values (ShapeCandidates), principal point at the image centre,
// distortion zero. Each candidate solves PnP on a few views spread over the recording and is
// scored by the median of their reprojection RMS; the lowest score wins. Near the true values
// PnP's reprojection error is small for every view; far from them no pose explains the corners.
#ifndef SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_
#define SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_

#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/intrinsics/target_view.h"

namespace splinecal {

inline constexpr int kFocalSteps = 48;
inline constexpr double kMinFocalWidths = 0.1;
inline constexpr double kMaxFocalWidths = 3.0;
inline constexpr int kInitViews = 12;  // views PnP is run on per candidate

// The candidate shapes of `model` (its projection and distortion; values ignored but width,
// height): the model's shape parameters at a few values across their range, distortion zero.
std::vector<Camera> ShapeCandidates(const Camera& model);

struct InitialIntrinsics {
  bool ok = false;
  Camera camera;
  double median_rms_px = 0.0;  // the winner's score
  std::string description;     // what was tried and what won, in words
};

// `views` of one camera (at least one with 6 corners). ok = false when no candidate could
// place the target in any view.
InitialIntrinsics InitialiseIntrinsics(const Camera& model,
                                       const std::vector<const TargetView*>& views);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_
