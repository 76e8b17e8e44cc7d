// The gauge of a free target (target_deformation.h, kind "points"): inner constraints that keep
// the refined target's centroid, orientation and size those of the file.
//
// A target whose every point p_i moves by its own offset c_i shares 7 directions with the views'
// poses: moving the whole target rigidly, or scaling it about any point, and moving every pose
// the opposite way (scaled by the same factor: a target k times larger at k times the distance
// projects alike) changes no residual. The offsets are fixed in those directions by requiring
// them to have no component of an infinitesimal similarity transform of the file's points,
//
//   sum_i G_i^T c_i = 0,   G_i = [ I_3 | -[q_i]x | q_i ],   q_i = p_i - mean_j p_j        (1)
//
// (columns: translation, rotation, scale; the free points only). These are the inner
// constraints of a free network adjustment: of all offsets that fit the views alike, the one
// nearest to the file's target in the least-squares sense. The rest is the target's shape, which
// the views determine. (1) joins the problem as 7 residuals w sum_i G_i^T c_i, w = 1 /
// kTargetGaugeStdM. The data's gradient has no component in these directions (they change no
// residual), so (1) holds exactly at the solution whatever w; w only has to make them
// determined without swamping the rest of the Gauss-Newton matrix: a free point seen in a
// thousand views at 1 m carries about 1e9 / m^2 of information, the constraint 1e12 / m^2, and
// the gauge's share of an offset's reported variance is about (1 um)^2 against (40 um)^2.
//
// The intrinsics, the rig's extrinsics and the offsets' differences do not depend on the gauge;
// the offsets themselves are reported in it.
#ifndef SPLINECAL_INTRINSICS_TARGET_POINTS_GAUGE_H_
#define SPLINECAL_INTRINSICS_TARGET_POINTS_GAUGE_H_

#include <ceres/cost_function.h>

#include <Eigen/Core>
#include <vector>

namespace splinecal {

inline constexpr double kTargetGaugeStdM = 1e-6;

// The G_i of (1) stacked: a 3 n x 7 matrix, rows 3 i to 3 i + 2 point i's (its offset under a
// small translation, rotation and scale of all the points about their mean).
Eigen::MatrixXd TargetSimilarityGenerators(const std::vector<Eigen::Vector3d>& points);

// Parameter blocks: the free points' offsets c_i (3 each), in the order of `points` (their file
// positions p_i). Residuals: the 7 of (1) divided by kTargetGaugeStdM.
class TargetPointsGaugeCost : public ceres::CostFunction {
 public:
  explicit TargetPointsGaugeCost(const std::vector<Eigen::Vector3d>& points);

  bool Evaluate(double const* const* parameters,
                double* residuals,
                double** jacobians) const override;

 private:
  std::vector<Eigen::Matrix<double, 7, 3>> generators_t_;  // G_i^T / kTargetGaugeStdM
};

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TARGET_POINTS_GAUGE_H_
