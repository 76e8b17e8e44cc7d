// Whether a corner agrees with its neighbours on the target, judged from the observed pixels
// alone (no camera model): the model-free half of the outlier test (intrinsics/corner_outliers.h).
//
// A planar target maps to the image by a smooth function of its plane coordinates (x, y): a
// homography bent by the lens's distortion. Over a corner's few nearest neighbours that function
// is close to its second-order Taylor expansion, so each pixel coordinate is fitted as
//
//   u(x, y) = a0 + a1 dx + a2 dy + a3 dx^2 + a4 dx dy + a5 dy^2,   dx, dy relative to the corner,
//
// by least squares over the corner's kLocalFitNeighbours nearest neighbours in the same view (the
// corner itself left out), and the corner's residual is its observed pixel minus a0, divided by
// sqrt(1 + h), h = e0^T (A^T A)^-1 e0 with e0 = (1, 0, 0, 0, 0, 0) and A the fit's design: with
// independent corner noise of std sigma the prediction's error has std sigma sqrt(1 + h), so the
// divided residual has std sigma wherever the corner sits. A corner on the board's edge or
// corner, extrapolated from neighbours on one side, has h of several and would otherwise look
// like an outlier for its noise alone. The
// quadratic absorbs the distortion's curvature; what it leaves is the third-order term: through
// EuRoC cam0's lens (k1 = -0.28, 459 px focal length), noise-free, for a view of EuRoC's AprilGrid
// reaching 410 px from the image centre (the corners are at 446 px), at most 0.07 px
// (local_corner_fit_test.cc), against up to 24 px of radtan's misfit there (docs/intrinsics.md,
// "Outliers").
// A detector's gross error (a corner of the wrong tag, a reflection, a mislabelled id) is
// inconsistent with its neighbours and shows here whatever the camera model.
#ifndef SPLINECAL_INTRINSICS_LOCAL_CORNER_FIT_H_
#define SPLINECAL_INTRINSICS_LOCAL_CORNER_FIT_H_

#include <Eigen/Core>
#include <vector>

namespace splinecal {

// Neighbours per fit: 6 coefficients per coordinate, 4 more for redundancy, so that one bad
// neighbour does not hide a bad corner.
inline constexpr int kLocalFitNeighbours = 10;

// Per corner of one view (p_t: target coordinates, z = 0 on a planar target; uv: observed
// pixels): the observed pixel minus the neighbours' quadratic prediction, divided by
// sqrt(1 + h) [px]. NaN where the
// corner cannot be judged: fewer than kLocalFitNeighbours other corners, neighbours that do not
// determine a quadratic (all on one line), or a target point off the plane z = 0.
std::vector<Eigen::Vector2d> LocalFitResiduals(const std::vector<Eigen::Vector3d>& p_t,
                                               const std::vector<Eigen::Vector2d>& uv);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_LOCAL_CORNER_FIT_H_
