// A starting point for a camera's intrinsics from target views alone, for any camera model
// (calib/calibrate_intrinsics.h, step 2).
//
// A homography (Zhang's method) assumes a pinhole: a fisheye or an omnidirectional lens maps
// straight target lines to curves, and its focal length is not where a pinhole fit puts it.
// Instead, every candidate camera of the model itself is tried: focal lengths on a geometric
// grid (fu = fv = f, kFocalSteps values from kMinFocalWidths to kMaxFocalWidths image widths)
// times the model's shape values (ShapeCandidates), principal point at the image centre,
// distortion zero. Each candidate solves PnP on kInitViews views and is scored by the median of
// their reprojection RMS; the lowest score wins. Near the true values PnP's reprojection error
// is small for every view; far from them no pose explains the corners.
//
// The views scored are those with the most perspective, spread over the recording (SweepViews
// in the .cc). A view without depth spread (fronto-parallel, or far) fits every focal length
// alike: f trades with the distance. When most scored views were such, the median was flat in
// f at the undistorted candidates' misfit of the lens distortion, and its minimum fell at the
// grid's edge: simulated EuRoC radtan lens, 24 views, seed 5, 7 of the 12 views (then the
// fullest of each time run) within 12 deg of fronto-parallel: 75.2 px for a true 458.7. The
// 12 views with the largest depth spread put it at 416.7 px (0.91 of the truth).
//
// The sweep is coarse to fine (kCoarseToFine): every kCoarseFocalStride-th focal step of every
// shape first, then the skipped steps within kCoarseFocalStride - 1 of the kCoarseSeeds best of
// those. A candidate's PnP solves stop once its median cannot beat the score it is compared
// with (exact: the upper median is >= that score once half the views are). It assumes the best
// candidate lies within 3 steps (a factor 1.25) of one of the two best coarse ones. Measured
// against the exhaustive sweep (kExhaustive): the same candidate (focal, shape, score bit for
// bit) in the 16 sweeps of initial_intrinsics_test.cc and on EuRoC cam0/cam1 (observations.csv,
// views of 12 corners or more) with pinhole-radtan (f 448.9 / 386.8 px), ds-none (359.0 px,
// shape (-0.2, 0.6)) and pinhole-equi (448.9 px); 23 of 56 candidates solved for radtan and
// equi, 54 of 168 for ds-none. A winner at the grid's first or last step is flagged
// (at_grid_edge) with a one-line warning: the lens may lie beyond the grid.
#ifndef SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_
#define SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_

#include <cstddef>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/intrinsics/target_view.h"

namespace splinecal {

// Focal lengths in image widths: 0.1 (a pinhole's 157 deg horizontal field of view; fisheye
// models put their focal length lower than a pinhole's for the same field of view) to 6 (9.5
// deg), 56 steps 7.7% apart.
inline constexpr int kFocalSteps = 56;
inline constexpr double kMinFocalWidths = 0.1;
inline constexpr double kMaxFocalWidths = 6.0;
inline constexpr int kInitViews = 12;  // views PnP is run on per candidate
inline constexpr int kCoarseFocalStride = 4;  // coarse pass: 1.077^4 = 1.35 apart
inline constexpr size_t kCoarseSeeds = 2;     // coarse candidates refined

enum class IntrinsicsSweep {
  kCoarseToFine,
  kExhaustive,  // every focal step of every shape (the tests' reference)
};

// The candidate shapes of `model` (its projection and distortion; values ignored but width,
// height): the model's shape parameters at a few values across their range, distortion zero.
std::vector<Camera> ShapeCandidates(const Camera& model);

struct InitialIntrinsics {
  bool ok = false;
  Camera camera;
  double median_rms_px = 0.0;  // the winner's score
  std::string description;     // what was tried and what won, in words
  // The winner is the grid's smallest or largest focal length; `warning` says so in one line.
  bool at_grid_edge = false;
  std::string warning;
};

// `views` of one camera (at least one with 6 corners). ok = false when no candidate could
// place the target in any view.
InitialIntrinsics InitialiseIntrinsics(
    const Camera& model,
    const std::vector<const TargetView*>& views,
    IntrinsicsSweep sweep = IntrinsicsSweep::kCoarseToFine);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_INITIAL_INTRINSICS_H_
