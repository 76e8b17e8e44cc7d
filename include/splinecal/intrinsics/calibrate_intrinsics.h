// Camera intrinsics and the rig's camera-to-camera extrinsics from calibration-target views
// (`splinecal intrinsics`, docs/intrinsics.md is the user's guide; this comment is the contract).
//
// The problem: every camera n of the rig has its model's intrinsics (camera/camera_model.h,
// only Camera::ActiveIntrinsics() vary) and, for n > 0, the pose T_cn_c0 of camera 0 in it; every
// timestamp k at which some camera sees the target has the target's pose in camera 0, T_c0_t(k):
//
//   minimise  sum_views sum_corners |r|^2          r: intrinsics/rig_reprojection_cost.h
//
// and, with IntrinsicsOptions::target_deformation, the target's shape or in-plane layout shared by
// every view (intrinsics/target_deformation.h; its gauge is said there).
//
// Gauge: camera 0 is the rig's frame; nothing else is free.
//
// Steps (each reported in the result, so the user sees what was used and why):
//   1. Views. The observations are grouped by (timestamp, camera); corners whose point id the
//      target lacks are dropped; a view needs min_corners corners.
//   2. Initial intrinsics (cameras without given values). A sweep over the focal length f on a
//      geometric grid from 0.1 to 6 image widths and over the model's shape parameter (omni
//      xi, eucm alpha, ds alpha, fov w; the model's distortion at 0), the principal point at
//      the image centre: every candidate camera solves PnP (camera/pnp.h) on up to
//      kInitViews views with the most perspective, spread over the recording, and the
//      candidate with the smallest median view RMS wins (a winner at the grid's edge is
//      warned about). The unprojection that PnP starts from is the candidate model's own, so a
//      fisheye or an omnidirectional lens starts from a fisheye or omnidirectional guess, not
//      from a pinhole homography that cannot describe it.
//   3. Target poses by PnP with the initial camera; a view whose PnP fails is dropped (reason
//      in ViewRecord). Views that repeat an earlier view of the same camera (rotation within
//      duplicate_rotation_deg and position within duplicate_distance_ratio of its distance)
//      are set aside (unless keep_repeated_views): a camera held still adds copies of one view
//      that would dominate the weights and the standard deviations would shrink with the number
//      of copies.
//   4. The rig: T_cn_c0 from the views where camera n and an already placed camera see the
//      target at the same timestamp (the candidate closest to all others, then the mean of the
//      candidates near it); a camera that never shares a timestamp with a placed one is an
//      error. T_c0_t(k) from camera 0's PnP, else from another camera's through the rig.
//   5. Solve (Levenberg-Marquardt, Schur complement on the target poses) with Huber's loss at
//      huber_px; then outlier rejection: a corner goes when its error beyond its image cell's
//      median error exceeds outlier_sigmas x the robust scale of its view and of its cell
//      (intrinsics/corner_outliers.h: a model's misfit of a region is not an outlier;
//      outlier_sigmas = 0: none goes), views left with fewer than min_corners corners are
//      removed, a warning names a large share and where it sits; then the
//      problem is solved again without the loss, residuals weighted by 1 / sigma.
//   6. Standard deviations: the marginal covariance of the intrinsics and extrinsics
//      (estimation/marginal_covariance.h), per coordinate the largest of the noise model's
//      and, where significant (ReportedCovarianceOf), two cluster-robust ones: over time blocks
//      whose length the residuals' autocorrelation chooses (intrinsics/time_blocks.h: errors
//      that nearby frames share) and over kinds of view, by image region and tilt
//      (estimation/view_clusters.h: model error that depends on the view).
//   7. Observability: the information matrix of each camera's intrinsics with the target poses
//      marginalised; parameters with a standard deviation above their threshold (focal lengths
//      and principal point: kUndeterminedPixelRatio of the image width; shape and distortion
//      parameters: kUndeterminedShapeStd) are named in a warning with what the views lack
//      (tilt, image coverage, number of views).
#ifndef SPLINECAL_INTRINSICS_CALIBRATE_INTRINSICS_H_
#define SPLINECAL_INTRINSICS_CALIBRATE_INTRINSICS_H_

#include <Eigen/Core>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <vector>

#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/parameter_covariance.h"
#include "splinecal/camera/reprojection_sample.h"
#include "splinecal/camera/target.h"
#include "splinecal/estimation/options.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/intrinsics/target_points_check.h"
#include "splinecal/intrinsics/time_blocks.h"
#include "splinecal/lie/se3.h"

namespace splinecal {

// One camera to calibrate: the model and image size, and whether its values are a starting
// point (from a camchain) or to be initialised from the data.
struct IntrinsicsCameraSpec {
  Camera camera;                // projection, distortion, width, height (+ values if given)
  bool initial_values = false;  // start from camera's values instead of the sweep
};

struct IntrinsicsOptions {
  int min_corners = 12;                     // a view needs at least this many corners
  double huber_px = 2.0;                    // first solve's Huber threshold [px] (0: none)
  double outlier_sigmas = 5.0;              // corners beyond this many sigma go (0: none)
  double duplicate_rotation_deg = 0.5;      // a view this close to an earlier one is a repeat...
  double duplicate_distance_ratio = 0.005;  // ...when its position is this close too
  // true: repeats stay (step 3 is skipped). With outlier_sigmas = 0 and huber_px = 0 the result
  // is then the exact least-squares solution over every offered view, the problem OpenCV's
  // calibrateCamera solves (docs/intrinsics.md, "Exact least squares").
  bool keep_repeated_views = false;
  int max_views_per_camera = 0;  // 0: every distinct view; else evenly thinned to this many
  // Camera-to-camera extrinsics: estimated (true) or held at the given T_cn_c0 (false).
  bool estimate_extrinsics = true;
  std::vector<SE3d> T_cn_c0_given;  // with estimate_extrinsics = false: one per camera
  // The target's geometry, shared by every view (target_deformation.h): none (as the file
  // says), a quadratic or cubic surface out of its plane, or in-plane (an AprilGrid's x/y
  // anisotropy, shear and tag-size ratio) estimated with the intrinsics, or in-plane-per-view
  // (the tag-size ratio each view's own: the corner detector's blur bias).
  TargetDeformationKind target_deformation = TargetDeformationKind::kNone;
  SolverOptions solver;
  CovarianceOptions covariance;
};

// Why a view was used or not (the report lists them).
enum class ViewStatus { kUsed, kTooFewCorners, kPnpFailed, kRepeat, kThinned, kOutlier };
const char* ViewStatusName(ViewStatus status);  // in words, e.g. "repeats an earlier view"
const char* ViewStatusKey(ViewStatus status);   // a result.yaml key, e.g. "repeats"

struct ViewRecord {
  int64_t t_ns = 0;
  int cam_id = 0;
  ViewStatus status = ViewStatus::kUsed;
  int corners = 0;           // in the observations (with a known point id)
  int corners_rejected = 0;  // outliers removed
  double rms_px = std::numeric_limits<double>::quiet_NaN();  // final RMS of the used corners
};

struct IntrinsicsCameraResult {
  Camera camera;
  std::vector<int> active;  // indices of the estimated intrinsics (Camera::ActiveIntrinsics)
  // Standard deviation per intrinsics entry, layout of camera/camera_model.h; NaN where held.
  Eigen::Matrix<double, kNumIntrinsics, 1> intrinsics_std =
      Eigen::Matrix<double, kNumIntrinsics, 1>::Constant(std::numeric_limits<double>::quiet_NaN());
  // The covariance of the active intrinsics, in `active` order.
  Eigen::MatrixXd intrinsics_covariance;
  double reprojection_rms_px = 0.0;
  // The pixel noise std the final solve weighted this camera's corners with: measured from its
  // residuals (sqrt of their sum of squares over the redundancy) [px].
  double pixel_sigma_px = 1.0;
  int views_offered = 0;
  int views_used = 0;
  int corners_used = 0;
  int corners_rejected = 0;
  // Camera n > 0: T_cn_c0 and T_cn_cnm1 (camera n-1 into camera n) with the std of their right
  // tangent [rho (m); phi (rad)]; identity and NaN for camera 0.
  SE3d T_cn_c0;
  SE3d T_cn_cnm1;
  Eigen::Matrix<double, 6, 1> T_cn_cnm1_std =
      Eigen::Matrix<double, 6, 1>::Constant(std::numeric_limits<double>::quiet_NaN());
  bool extrinsic_estimated = false;
  std::string initialisation;  // how the start was found, in words
  // The covariance of the active intrinsics (Kalibr's order) and, for n > 0 with an estimated
  // extrinsic, T_cn_cnm1's right tangent (camera/parameter_covariance.h), for camchain.yaml; and per
  // intrinsic of it where its std comes from: "noise" (the noise model), "time blocks" or
  // "view clusters" (the cluster-robust one over time blocks or over kinds of view, step 6).
  ParameterCovariance covariance;
  std::vector<std::string> std_from;
};

// The estimated target shape (IntrinsicsOptions::target_deformation).
struct TargetDeformationResult {
  TargetShape shape;             // kind none: flat, nothing below is filled
  Eigen::VectorXd coefficients;  // c (target_deformation.h): heights [m] or in-plane ratios
  // Of c (with the intrinsics' inflation), empty without stds; every point free: of the free
  // points' offsets stacked in id order (x, y, z each; x, y with z held).
  Eigen::MatrixXd covariance;
  // The surface relative to the least-squares plane through the target's points, at its centre
  // and corners (target_deformation.h): heights_m = heights.M c, with their stds (empty in
  // plane).
  TargetDeformationHeights heights;
  Eigen::VectorXd heights_m;
  Eigen::VectorXd heights_std_m;
  // In-plane-per-view: each timestamp's inset d_v (target_deformation.h), without stds.
  std::map<int64_t, double> view_inset;
  // Every point free: each free point's offset from the file's position [m] and its std (in the
  // gauge of intrinsics/target_points_gauge.h), and the refined target: every point of the file,
  // the free ones moved (a "points" target, camera/target.h, for the next step's --target).
  std::map<int64_t, Eigen::Vector3d> point_offsets_m;
  std::map<int64_t, Eigen::Vector3d> point_offsets_std_m;
  CalibrationTarget refined_target;
};

struct IntrinsicsResult {
  std::vector<IntrinsicsCameraResult> cameras;
  TargetDeformationResult target_deformation;
  // With the file's layout (target_deformation none): the test of every point's position against
  // the file's (target_points_check.h); empty otherwise.
  TargetPointsCheck target_points_check;
  std::vector<ViewRecord> views;              // every view offered, by (t_ns, cam_id)
  std::vector<ReprojectionSample> residuals;  // the used corners
  // The corners the outlier pass removed, with their errors when they were removed.
  std::vector<ReprojectionSample> removed_corners;
  // T_c0_t per used timestamp, for the report and tests.
  std::vector<std::pair<int64_t, SE3d>> target_poses;
  SolveSummary solve;
  // The time blocks of the cluster-robust covariance (intrinsics/time_blocks.h) and how many
  // the recording held.
  TimeBlocks time_blocks;
  int time_blocks_count = 0;
  // The occupied view clusters of the second cluster-robust covariance (view_clusters.h); it is
  // used when there are at least kMinViewClusters.
  int view_clusters_count = 0;
  std::vector<std::string> warnings;
};

// Throws splinecal::Error in plain words for: no camera, an observation of a camera without a
// spec, a camera with no usable view, a camera the rig cannot place (no timestamp shared with
// another camera), a failed solve.
IntrinsicsResult CalibrateIntrinsics(const std::vector<Observation>& observations,
                                     const CalibrationTarget& target,
                                     const std::vector<IntrinsicsCameraSpec>& cameras,
                                     const IntrinsicsOptions& options);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_CALIBRATE_INTRINSICS_H_
