// The whole public API of splinecal in one include, as ceres/ceres.h is for Ceres:
//
//   #include <splinecal/splinecal.h>
//
// Areas, from the bottom up: an area includes only areas listed before it, so no two areas
// include each other (tests/architecture/layering_test.cc checks both).
//   lie/         SO(3), SE(3), their Jacobians and Ceres manifolds
//   spline/      the uniform cubic B-spline of SE(3) poses (coupled SE(3) or split SO(3) x R^3),
//                its knot layout and derivatives
//   imu/         IMU samples, the measurement models (Kalibr's), noise densities, dead reckoning
//   camera/      camera models, camchains, targets, observations, PnP, rolling shutter
//   io/          readers and writers of every file format (plain data types in, out)
//   plot/        SVG plots and the one plot decimation (knows nothing of what it plots)
//   detect/      target corners in images (library splinecal::detect: OpenCV, libapriltag)
//   estimation/  residuals, the spline problem, covariance, solver rounds: the estimation core
//   vio/         preintegration, hand-eye, visual-inertial alignment, clock correlation
//   sim/         IMU and camera simulation, trajectories, noise
//   allan/       Allan deviation and noise identification
//   calib/       fit (IMU + poses) and calibrate (camera-IMU)
//   intrinsics/  camera intrinsics and the rig's camera-to-camera poses (`splinecal intrinsics`)
//   report/      the result files of every command and the HTML reports (one writer)
// (cli/, the command-line front end, sits on top and is not part of the library.)
// docs/library.md shows a complete program. Each header's comment is its contract.
#ifndef SPLINECAL_SPLINECAL_H_
#define SPLINECAL_SPLINECAL_H_

#include "splinecal/axis_name.h"
#include "splinecal/enum_names.h"
#include "splinecal/error.h"
#include "splinecal/median.h"
#include "splinecal/memory_reuse.h"
#include "splinecal/run_tasks.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"

// lie/
#include "splinecal/lie/se3.h"
#include "splinecal/lie/se3_manifold.h"
#include "splinecal/lie/so3.h"
#include "splinecal/lie/types.h"

// spline/
#include "splinecal/spline/angular_acceleration_jacobian.h"
#include "splinecal/spline/basis.h"
#include "splinecal/spline/knot_layout.h"
#include "splinecal/spline/se3_spline.h"
#include "splinecal/spline/segment.h"
#include "splinecal/spline/segment_jacobians.h"
#include "splinecal/spline/split_segment.h"
#include "splinecal/spline/split_segment_jacobians.h"
#include "splinecal/spline/trajectory_evaluation.h"
#include "splinecal/spline/trajectory_model.h"

// imu/
#include "splinecal/imu/correct_imu.h"
#include "splinecal/imu/ground_truth.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/imu_intrinsics.h"
#include "splinecal/imu/imu_model.h"
#include "splinecal/imu/imu_model_kind.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/imu/imu_sample.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/imu/matrix_parameters.h"
#include "splinecal/imu/noise.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/imu/scale_misalignment_model.h"
#include "splinecal/imu/size_effect_model.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/imu/static_recording.h"

// camera/
#include "splinecal/camera/camchain.h"
#include "splinecal/camera/camera_model.h"
#include "splinecal/camera/distortion.h"
#include "splinecal/camera/image_bounds_check.h"
#include "splinecal/camera/observation_gates.h"
#include "splinecal/camera/observations.h"
#include "splinecal/camera/parameter_covariance.h"
#include "splinecal/camera/pnp.h"
#include "splinecal/camera/projection.h"
#include "splinecal/camera/reprojection_sample.h"
#include "splinecal/camera/rolling_shutter.h"
#include "splinecal/camera/target.h"
#include "splinecal/camera/target_layout_check.h"

// io/
#include "splinecal/io/bag_imu.h"
#include "splinecal/io/bag_messages.h"
#include "splinecal/io/bag_reader.h"
#include "splinecal/io/calibration_export.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/camchain_yaml_covariance.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/image_folder.h"
#include "splinecal/io/imu_models_yaml.h"
#include "splinecal/io/imu_units.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/number_parser.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/parallel_euroc_imu.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/io/static_recording.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/io/text_file.h"
#include "splinecal/io/yaml_document.h"
#include "splinecal/io/yaml_transforms.h"
#include "splinecal/io/yaml_writer.h"

// plot/
#include "splinecal/plot/plot_decimation.h"
#include "splinecal/plot/svg_plot.h"

// detect/ (link splinecal::detect)
#include "splinecal/detect/bag_extract.h"
#include "splinecal/detect/bag_image.h"
#include "splinecal/detect/detect_bag.h"
#include "splinecal/detect/detect_folders.h"
#include "splinecal/detect/gray_image.h"
#include "splinecal/detect/image_file.h"
#include "splinecal/detect/saddle_point.h"
#include "splinecal/detect/target_detector.h"

// estimation/
#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/bias_spline.h"
#include "splinecal/estimation/gravity_manifold.h"
#include "splinecal/estimation/gravity_tangent.h"
#include "splinecal/estimation/imu_model_observability.h"
#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/estimation/imu_noise_estimate.h"
#include "splinecal/estimation/imu_noise_mode.h"
#include "splinecal/estimation/interval_manifold.h"
#include "splinecal/estimation/knot_spacing.h"
#include "splinecal/estimation/marginal_covariance.h"
#include "splinecal/estimation/model_noise_cluster.h"
#include "splinecal/estimation/options.h"
#include "splinecal/estimation/pose_fit.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/estimation/solve_rounds.h"
#include "splinecal/estimation/solver_progress.h"
#include "splinecal/estimation/spline_evaluation_callback.h"
#include "splinecal/estimation/spline_problem.h"
#include "splinecal/estimation/variance_components.h"
#include "splinecal/estimation/view_clusters.h"

// vio/
#include "splinecal/vio/align.h"
#include "splinecal/vio/hand_eye.h"
#include "splinecal/vio/preintegration.h"
#include "splinecal/vio/time_offset_correlation.h"

// sim/
#include "splinecal/sim/noise_generator.h"
#include "splinecal/sim/simulate_camera.h"
#include "splinecal/sim/simulate_imu.h"
#include "splinecal/sim/simulation_result.h"
#include "splinecal/sim/simulation_trajectory.h"
#include "splinecal/sim/trajectories.h"

// allan/
#include "splinecal/allan/allan.h"
#include "splinecal/allan/allan_deviation.h"
#include "splinecal/allan/edf.h"
#include "splinecal/allan/motion.h"
#include "splinecal/allan/noise_fit.h"
#include "splinecal/allan/slope_lines.h"
#include "splinecal/allan/work_budget.h"

// calib/
#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/calibrate_run.h"
#include "splinecal/calib/camchain_prior.h"
#include "splinecal/calib/camera_selection.h"
#include "splinecal/calib/consider_covariance.h"
#include "splinecal/calib/fit.h"
#include "splinecal/calib/imu_covariance.h"

// intrinsics/
#include "splinecal/intrinsics/calibrate_intrinsics.h"
#include "splinecal/intrinsics/camera_specs.h"
#include "splinecal/intrinsics/compare_models.h"
#include "splinecal/intrinsics/corner_outliers.h"
#include "splinecal/intrinsics/initial_intrinsics.h"
#include "splinecal/intrinsics/intrinsics_observability.h"
#include "splinecal/intrinsics/local_corner_fit.h"
#include "splinecal/intrinsics/rig_reprojection_cost.h"
#include "splinecal/intrinsics/robust_mean_pose.h"
#include "splinecal/intrinsics/target_deformation.h"
#include "splinecal/intrinsics/target_points_check.h"
#include "splinecal/intrinsics/target_points_gauge.h"
#include "splinecal/intrinsics/target_view.h"
#include "splinecal/intrinsics/time_blocks.h"

// report/
#include "splinecal/report/align_report.h"
#include "splinecal/report/allan_report.h"
#include "splinecal/report/calibrate_report.h"
#include "splinecal/report/command_outputs.h"
#include "splinecal/report/correct_report.h"
#include "splinecal/report/detect_report.h"
#include "splinecal/report/evaluate_report.h"
#include "splinecal/report/fit_report.h"
#include "splinecal/report/html_page.h"
#include "splinecal/report/imu_model_report.h"
#include "splinecal/report/integrate_report.h"
#include "splinecal/report/intrinsics_report.h"
#include "splinecal/report/option_names.h"
#include "splinecal/report/report_inputs.h"
#include "splinecal/report/reprojection_figures.h"
#include "splinecal/report/simulate_report.h"
#include "splinecal/report/target_points_figure.h"

#endif  // SPLINECAL_SPLINECAL_H_
