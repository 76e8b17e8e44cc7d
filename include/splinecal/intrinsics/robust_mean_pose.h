// The pose that a set of noisy, partly wrong estimates of one rigid transform agree on: a
// camera-to-camera extrinsic T_cn_c0 from the views in which both cameras placed the target
// (T_cn_t T_c0_t^-1 per shared timestamp), where a few PnP poses are off (a flipped planar
// pose, a view with motion blur).
//
//   1. The medoid: the candidate whose median distance to the others is smallest, with
//      distance d(A, B) = |Log(R_A^T R_B)| + |t_A - t_B| / s (radians plus translation in units
//      of s, the candidates' median translation norm, so neither part dominates by its unit).
//      At most kMedoidCandidates candidates (evenly spaced) are tried as the medoid.
//   2. The mean of the candidates within 3x the medoid's median distance: translations
//      averaged, rotations by the normalised sum of their quaternions (signs aligned with the
//      medoid's), the chordal L2 mean, which is accurate to second order for rotations this
//      close together.
#ifndef SPLINECAL_INTRINSICS_ROBUST_MEAN_POSE_H_
#define SPLINECAL_INTRINSICS_ROBUST_MEAN_POSE_H_

#include <vector>

#include "splinecal/lie/se3.h"

namespace splinecal {

inline constexpr int kMedoidCandidates = 200;

// `candidates` must not be empty. *inliers (may be nullptr) counts the candidates averaged.
SE3d RobustMeanPose(const std::vector<SE3d>& candidates, int* inliers = nullptr);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_ROBUST_MEAN_POSE_H_
