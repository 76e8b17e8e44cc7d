// The lens as a one-parameter division model about the image centre, fitted to the tags found in
// one frame, for placing the tags the search missed (private to src/detect/).
//
// The grid's tags are predicted from found ones by a homography (grid_prediction.h,
// aprilgrid_detector.cc). A homography is the image of a plane through a pinhole; a lens bends
// straight lines, and through a fisheye the bend over a tag or two is several pixels at the
// image's edge: on a rendered 512 x 512 double-sphere fisheye (TUM-VI's lens), predictions of
// the outer tags from their inner neighbours were 9-10 px off, beyond the 5 px the saddle
// refinement may move a corner, and those tags were lost. The division model
//   p_u = c + (p - c) / (1 + lambda |p - c|^2)
// [Fitzgibbon01] straightens most of such a bend with one parameter. lambda is the value under
// which one homography best maps the found tags' grid points to their undistorted pixels (the
// pixel error measured back in the image); the homography is then fitted in the undistorted
// image, and its predictions mapped back by the model's inverse
//   r = (1 - sqrt(1 - 4 lambda r_u^2)) / (2 lambda r_u)    (r_u = |p_u - c|, r = |p - c|).
// With lambda = 0 (too few tags to fit it, or a lens without distortion) this is the
// homography alone.
//
// [Fitzgibbon01] A. W. Fitzgibbon, "Simultaneous linear estimation of multiple view geometry and
// lens distortion", CVPR 2001.
#ifndef SPLINECAL_SRC_DETECT_DIVISION_MODEL_H_
#define SPLINECAL_SRC_DETECT_DIVISION_MODEL_H_

#include <vector>

#include <opencv2/core.hpp>

#include "grid_tag.h"
#include "splinecal/camera/target.h"

namespace splinecal {

struct DivisionModel {
  cv::Point2d centre;
  double lambda = 0.0;  // [1 / px^2]

  // False at and beyond the model's pole (barrel, lambda < 0: 1 + lambda |p - c|^2 <= 0).
  bool Undistort(const cv::Point2d& p, cv::Point2d* u) const;
  // False where the model has no inverse (pincushion, lambda > 0, beyond its fold).
  bool Distort(const cv::Point2d& u, cv::Point2d* p) const;

  // The pixels of the grid-plane points `query` by the homography from (plane, pixels) fitted in
  // the undistorted image. False for fewer than 4 pairs, a degenerate fit, or a point the model
  // cannot map back.
  bool Predict(const std::vector<cv::Point2d>& plane,
               const std::vector<cv::Point2d>& pixels,
               const std::vector<cv::Point2d>& query,
               std::vector<cv::Point2d>* predicted) const;
};

// The division model of `tags` (corners in an image of `size`) whose single homography from
// their grid points fits them best; lambda = 0 with fewer than kMinTagsForDivisionModel tags.
DivisionModel FitDivisionModel(const CalibrationTarget& target,
                               const std::vector<GridTag>& tags,
                               const cv::Size& size);

// Fewer found tags than this leave lambda at 0: a handful of tags near each other barely tells a
// bend from the perspective.
inline constexpr int kMinTagsForDivisionModel = 4;

}  // namespace splinecal

#endif  // SPLINECAL_SRC_DETECT_DIVISION_MODEL_H_
