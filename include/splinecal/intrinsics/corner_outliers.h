// Which corners of one camera are outliers (calibrate_intrinsics.h, step 5): a corner is an
// outlier when its error is far beyond the robust scale of its own view AND of its image
// neighbourhood, AND its observed pixel disagrees with its neighbours on the target; not merely
// when it is far from zero.
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
// and the model test fails when |d| > outlier_sigmas x max(s_c, s_v). That alone is not enough
// where the misfit is steepest: the image's extreme corners hold too few corners for a cell
// median, and there radtan's misfit grows by several pixels within one tag. On EuRoC cam0 (every
// 8th frame) it removed 16 corners with radtan errors up to 24 px that ds-none fits within
// 0.5 px, and moved cx 2.2 px away from the least-squares solution (docs/intrinsics.md,
// "Outliers"). So a corner must also fail the model-free test (intrinsics/local_corner_fit.h):
//
//   l        its observed pixel minus the quadratic through its neighbours on the target,
//   t_c, t_v 1.4826 x the median |l| component over the camera's and over the view's corners,
//
// |l| > outlier_sigmas x max(t_c, t_v). A mislabelled corner, a corner of a neighbouring tag or
// a reflection fails both; a corner the model cannot describe passes the second. Where l cannot
// be computed (a view with too few corners, a non-planar target) the model test decides alone.
#ifndef SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_
#define SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_

#include <Eigen/Core>
#include <string>
#include <vector>

namespace splinecal {

// A cell needs this many corners for its median misfit and its own scale.
inline constexpr int kMinCellCorners = 20;

// One view's corners: observed pixels, errors (predicted - observed; NaN where the model
// cannot project the corner: always an outlier) and target coordinates (empty: the model test
// decides alone).
struct ViewErrors {
  std::vector<Eigen::Vector2d> uv;
  std::vector<Eigen::Vector2d> error;
  std::vector<Eigen::Vector3d> p_t;
};

struct CornerOutliers {
  std::vector<std::vector<bool>> outlier;  // per view, per corner
  double sigma_px = 0.0;                   // 1.4826 x the median |e| component, camera-wide
  int removed = 0;
  int removed_at_border = 0;  // in the outer ring of cells
  int corners = 0;
  // Corners that failed the model test but agree with their neighbours on the target: kept
  // (the model misfits them), and how many of them sit in the outer ring of cells.
  int kept_misfit = 0;
  int kept_misfit_at_border = 0;
};

// The outliers of one camera's views (outlier_sigmas = 0: only corners without an error).
CornerOutliers FindCornerOutliers(const std::vector<ViewErrors>& views,
                                  int width,
                                  int height,
                                  double outlier_sigmas);

// The warning (empty when none): the count of removed corners when more than
// kOutlierWarningShare of the camera's went; and the corners the model misfits (kept_misfit)
// when more than that share, or at least kMinBorderCorners of them with more than 1.5x the
// border's share of the cells at the border, naming the likely misfit ("pinhole-radtan likely
// misfits the border (try pinhole-equi or ds-none)").
inline constexpr double kOutlierWarningShare = 0.01;
inline constexpr int kMinBorderCorners = 10;
std::string CornerOutlierWarning(const std::string& camera_name,
                                 const std::string& model_name,
                                 const CornerOutliers& outliers);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_CORNER_OUTLIERS_H_
