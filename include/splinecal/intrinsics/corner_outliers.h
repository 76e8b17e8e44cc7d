// Which corners of one camera are outliers (calibrate_intrinsics.h, step 5): a corner is an
// outlier when its error is far beyond the robust scale of its own view AND of its image
// neighbourhood, not merely far from zero.
//
// A camera model that misfits a region of the image (radtan at a wide lens's border) leaves
// every corner there with a large error of the same direction; a test against one camera-wide
// scale removes exactly those corners, and the fit then bends to the corners it kept: removal
// biases the model instead of cleaning the data. A blurred view (motion, focus) has larger
// errors everywhere in it; removing its corners one by one keeps the blurred view's good half.
// So, with the image in kCoverageCells x kCoverageCells cells (intrinsics_observability.h):
//
//   m_c      the median error vector of the camera's corners in cell c (the model's local
//            misfit; 0 in a cell with fewer than kMinCellCorners corners),
//   d        = e - m_c, the corner's error beyond its cell's misfit,
//   s_c      1.4826 x the median |d| component in cell c (the camera's, in a sparse cell),
//   s_v      1.4826 x the median |d| component in the corner's view,
//
// and the corner is an outlier when |d| > outlier_sigmas x max(s_c, s_v). A mislabelled corner,
// a corner of a neighbouring tag or a reflection lies far outside all of them.
#ifndef SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_
#define SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_

#include <Eigen/Core>
#include <string>
#include <vector>

namespace splinecal {

// A cell needs this many corners for its median misfit and its own scale.
inline constexpr int kMinCellCorners = 20;

// One view's corners: observed pixels and errors (predicted - observed; NaN where the model
// cannot project the corner: always an outlier).
struct ViewErrors {
  std::vector<Eigen::Vector2d> uv;
  std::vector<Eigen::Vector2d> error;
};

struct CornerOutliers {
  std::vector<std::vector<bool>> outlier;  // per view, per corner
  double sigma_px = 0.0;                   // 1.4826 x the median |e| component, camera-wide
  int removed = 0;
  int removed_at_border = 0;  // in the outer ring of cells
  int corners = 0;
};

// The outliers of one camera's views (outlier_sigmas = 0: only corners without an error).
CornerOutliers FindCornerOutliers(const std::vector<ViewErrors>& views,
                                  int width,
                                  int height,
                                  double outlier_sigmas);

// The warning when more than kOutlierWarningShare of a camera's corners went, or at least
// kMinBorderCorners went and more than 1.5x the border's share of the cells hold them (empty
// otherwise): the count, and where they sit, naming the likely misfit when it is the border. A
// few corners at the border weigh much: on EuRoC cam0 (every 8th frame, pinhole-radtan) 16
// corners in the image's top-right and bottom-left corners, with errors of 2 to 24 px pointing
// outward, moved cx by 2.2 px (docs/intrinsics.md, "Outliers").
inline constexpr double kOutlierWarningShare = 0.01;
inline constexpr int kMinBorderCorners = 10;
std::string CornerOutlierWarning(const std::string& camera_name,
                                 const std::string& model_name,
                                 const CornerOutliers& outliers);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_
