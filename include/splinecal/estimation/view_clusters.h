// The view clusters of a cluster-robust covariance over kinds of view: views grouped by where
// the target sits in the image and which way it tilts. Used by the intrinsics' second sandwich
// (intrinsics/calibrate_intrinsics.h, step 6) and by calibrate's (calib/calibrate.h: the target
// frames' corners re-estimate the intrinsics and carry the same view-dependent model error).
//
// The time blocks (time_blocks.h) see errors that nearby frames share. They cannot see a model
// error that depends on the view: a lens the model does not quite describe, a board that is not
// quite flat, a detector biased with scale or blur. The fit then balances views that pull the
// intrinsics apart, and a recording whose views fall elsewhere (its other half, another
// session) lands elsewhere. On the EuRoC calibration recording the two halves moved ds-none's
// pu by 3.3 px against time-block stds of 0.3-0.6 px, while their image regions and tilts
// differed (docs/intrinsics.md, "Error bars").
//
// The sandwich over clusters of similar views measures how much the views of one kind pull
// against the others: with g_k the score of cluster k at the solution, sum_k g_k g_k^T is of the
// size of the misfit between the kinds, and the resulting covariance is that of the estimate
// when the mix of view kinds changes. Where the model is right every g_k is noise and the
// sandwich agrees with the noise model (it is then not taken: ReportedCovarianceOf's test).
//
// Cluster of a view: the cell of a kViewClusterCells x kViewClusterCells grid of the image that
// holds its corners' centroid, times the quadrant of the target normal's direction in the image
// plane (the sign of its x and y components in the camera frame): up to 36 clusters.
#ifndef SPLINECAL_ESTIMATION_VIEW_CLUSTERS_H_
#define SPLINECAL_ESTIMATION_VIEW_CLUSTERS_H_

#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

inline constexpr int kViewClusterCells = 3;
// Fewer occupied clusters leave the sandwich's own scatter larger than what it would add.
inline constexpr int kMinViewClusters = 8;

// corners: the view's (at least one); T_c_t: the target's pose in the view's camera.
int ViewCluster(const Camera& camera,
                const std::vector<TargetCornerObservation>& corners,
                const SE3d& T_c_t);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_VIEW_CLUSTERS_H_
