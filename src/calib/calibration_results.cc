#include "calibration_problem.h"

#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <set>
#include <vector>

#include "imu_covariance_rows.h"
#include "splinecal/calib/consider_covariance.h"
#include "splinecal/estimation/model_noise_cluster.h"
#include "splinecal/estimation/view_clusters.h"
#include "splinecal/imu/imu_rate.h"

namespace splinecal {
namespace internal {

MarginalCovarianceOptions CalibrationProblem::CovarianceOptionsForProblem() {
  MarginalCovarianceOptions covariance_options;
  covariance_options.backend = CovarianceBackend::kSchur;
  covariance_options.num_threads = options_.solver.num_threads;
  imu_noise_->AddToCovarianceOptions(
      spline_.get(), options_.covariance.robust_window_s, &covariance_options);
  if (covariance_options.cluster_of && !prior_blocks_.empty()) {
    // A camchain prior is the intrinsics step's estimate with its covariance: its noise is that
    // step's error, stated by the covariance, not a sample of this recording's scatter. It joins
    // no time window (where the spline's TimeWindowOf would put a residual without a time) and
    // is no cluster of its own (whose realised pull, at the solution the data's pull against
    // it, would be taken as its noise): kModelNoiseCluster, its information as it is.
    const auto by_time = covariance_options.cluster_of;
    const std::set<ceres::ResidualBlockId> priors = prior_blocks_;
    covariance_options.cluster_of = [by_time, priors](ceres::ResidualBlockId id) {
      return priors.count(id) != 0 ? kModelNoiseCluster : by_time(id);
    };
  }
  return covariance_options;
}

int CalibrationProblem::ViewKindClusters(MarginalCovarianceOptions* options) {
  // The target frames' corners re-estimate the intrinsics here as in the intrinsics step, and
  // the intrinsics set the camera's pose: a focal length 1.4% off scales the target's distance,
  // so T_cam_imu's translation along the optical axis, and a principal point off turns it. A lens
  // model that fits some kinds of view better than others pulls the estimate apart by kind of
  // view, which time windows do not see: on the halves of EuRoC's imu_april, with time windows
  // alone, cam0's translation z differed by 8.3 combined std (docs/calibrate.md, "On EuRoC's
  // imu_april"). So each frame's residual joins the cluster of its camera, image cell and tilt
  // (estimation/view_clusters.h, as the intrinsics step clusters); every other residual keeps
  // its time window (the IMU's scatter is measured as in the first sandwich), a prior stays
  // model noise.
  if (!options->cluster_of || !options_.covariance.view_clusters) return 0;
  const SE3Splined spline = Spline();
  const SE3d T_w_t = PoseFromBlock(T_w_t_.data());
  std::map<ceres::ResidualBlockId, int> view_of;
  std::set<int> occupied;
  for (const FrameResidual& r : frame_residuals_) {
    const TargetFrame& frame = target_frames_[r.frame];
    const double t = std::clamp(TimeSinceT0(frame.t_ns) + cameras_[frame.cam].time_offset_s,
                                spline.start_time(), spline.end_time());
    const SE3d T_c_t = CameraFromImu(frame.cam) * spline.Pose(t).inverse() * T_w_t;
    // The cameras of a rig share the clusters, as in the intrinsics step: they see the target
    // at once, from nearly one side, and their errors of one kind of view go together.
    const int cluster = ViewCluster(camchain_[frame.cam].camera, frame.corners, T_c_t);
    view_of.emplace(r.id, cluster);
    occupied.insert(cluster);
  }
  if (static_cast<int>(occupied.size()) < kMinViewClusters) return 0;
  const int first_window = kViewClusterCells * kViewClusterCells * 4;
  const auto by_time = options->cluster_of;
  options->further_cluster_of.push_back(
      [by_time, view_of, first_window](ceres::ResidualBlockId id) {
        const auto found = view_of.find(id);
        if (found != view_of.end()) return found->second;
        const int window = by_time(id);
        return window == kModelNoiseCluster ? window : first_window + window;
      });
  return static_cast<int>(occupied.size());
}

bool CalibrationProblem::TargetScaleStd(double* std_out) {
  MarginalCovarianceOptions covariance_options = CovarianceOptionsForProblem();
  const MarginalCovariance marginal =
      ComputeMarginalCovariance(&problem(), {&target_scale_}, covariance_options);
  if (!marginal.ok) return false;
  *std_out = std::sqrt(std::max(0.0, ReportedCovarianceOf(marginal).covariance(0, 0)));
  return true;
}

void CalibrationProblem::HoldTargetScale() {
  // r(s p_t; T) = r(p_t; T / s) (calib/detail/target_scale_cost.h): the same pixels at s = 1.
  const double s = target_scale_;
  for (double* block : control_blocks()) {
    for (int i = 0; i < 3; ++i) block[i] /= s;
  }
  for (CameraState& cam : cameras_) {
    for (int i = 0; i < 3; ++i) cam.extrinsic[i] /= s;
  }
  for (Landmark& landmark : landmarks_) landmark.rho *= s;  // depths / s
  target_scale_ = 1.0;
  target_scale_free_ = false;
}

void CalibrationProblem::ComputeCovariance(CalibrationResult* result) {
  // The marginal covariance of the calibration parameters (estimation/marginal_covariance.h),
  // with every other free block -- control poses, bias spline, gravity, inverse depths -- as
  // nuisance. Always the kSchur backend (one sparse factorisation of the whole information): it
  // takes the 450 bias coordinates through their 6 time averages, one solve each, and refuses a
  // reported covariance whose correlation matrix is numerically singular.
  // Wanted: the cameras' blocks, then every bias control point; reported: the cameras' tangent
  // coordinates as they are and the biases' time averages (MeanBiasMap), q = A x.
  std::vector<const double*> wanted;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    if (!HeldToReference(c)) wanted.push_back(cameras_[c].extrinsic.data());
    if (EstimatesIntrinsics(c)) wanted.push_back(cameras_[c].intrinsics.data());
    if (options_.estimate_time_offset) wanted.push_back(&cameras_[c].time_offset_s);
    if (options_.rolling_shutter) wanted.push_back(&cameras_[c].line_delay);
  }
  std::map<const double*, int> offset;  // first row of each camera block in the covariance
  int num_camera = 0;
  for (const double* block : wanted) {
    offset[block] = num_camera;
    num_camera += problem().ParameterBlockTangentSize(block);
  }
  if (target_scale_free_) {
    offset[&target_scale_] = num_camera;
    wanted.push_back(&target_scale_);
    ++num_camera;
  }
  // The IMU model's blocks (none for kCalibrated), reported as they are.
  std::vector<double*> model_blocks;
  for (double* block : spline_->ImuModelBlocks()) {
    if (!problem().IsParameterBlockConstant(block)) model_blocks.push_back(block);
  }
  for (double* block : model_blocks) {
    offset[block] = num_camera;
    wanted.push_back(block);
    num_camera += problem().ParameterBlockTangentSize(block);
  }
  if (further_) further_->AddCovarianceBlocks(&problem(), &wanted, &offset, &num_camera);
  const int num_bias_points = spline_->bias_spline().num_points();
  for (int m = 0; m < num_bias_points; ++m) wanted.push_back(spline_->gyro_bias(m));
  for (int m = 0; m < num_bias_points; ++m) wanted.push_back(spline_->accel_bias(m));
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(num_camera + 6, num_camera + 6 * num_bias_points);
  A.topLeftCorner(num_camera, num_camera).setIdentity();
  A.bottomRightCorner(6, 6 * num_bias_points) = spline_->MeanBiasMap(imu_);
  MarginalCovarianceOptions covariance_options = CovarianceOptionsForProblem();
  covariance_options.reported_map = A;
  // The second sandwich, over kinds of view, from the same linearisation; each std is the
  // larger of the two.
  const int view_clusters = ViewKindClusters(&covariance_options);
  const MarginalCovariance marginal =
      ComputeMarginalCovariance(&problem(), wanted, covariance_options);
  if (!marginal.ok) {
    result->warnings.push_back(
        "the covariance could not be computed (the problem is rank deficient: some parameter is "
        "not determined by the data); standard deviations are not reported");
    return;
  }
  Eigen::VectorXd inflation = ReportedCovarianceOf(marginal).inflation;
  if (view_clusters > 0 && !marginal.further.empty()) {
    const MarginalCovariance& by_view_kind = marginal.further.front();
    if (by_view_kind.ok) {
      inflation = inflation.cwiseMax(ReportedCovarianceOf(by_view_kind).inflation);
      result->view_clusters = view_clusters;
    }
  }
  // Rows and columns scaled alike: the correlations stay the noise model's.
  Eigen::MatrixXd cov = inflation.asDiagonal() * marginal.covariance * inflation.asDiagonal();
  if (!CarryConsideredIntrinsics(wanted, A, &cov, result)) {
    result->warnings.push_back(
        "the considered intrinsics' uncertainty could not be carried (this recording's corners "
        "do not determine them); the standard deviations treat them as exact");
  }
  result->std_inflation = inflation.maxCoeff();
  result->robust_clusters = marginal.num_clusters;
  auto block = [&](const double* a, int rows) {
    return Eigen::MatrixXd(cov.block(offset[a], offset[a], rows, rows));
  };
  result->covariance_ok = true;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraState& cam = cameras_[c];
    CameraEstimate& estimate = result->cameras[c];
    // A held camera shares camera 0's right tangent (reprojection_cost.h, T_cam_cref).
    const Eigen::MatrixXd cov6 = block(ExtrinsicBlock(c), 6);
    const Eigen::Matrix3d R = CameraFromImu(c).rotationMatrix();
    const Eigen::Matrix3d cov_t = R * cov6.topLeftCorner<3, 3>() * R.transpose();
    estimate.translation_std_m = cov_t.diagonal().cwiseMax(0.0).cwiseSqrt();
    estimate.rotation_std_deg =
        cov6.bottomRightCorner<3, 3>().diagonal().cwiseMax(0.0).cwiseSqrt() * kRadToDeg;
    if (EstimatesIntrinsics(c)) {
      const std::vector<int> active = camchain_[c].camera.ActiveIntrinsics();
      const Eigen::MatrixXd cov_k = block(cam.intrinsics.data(), static_cast<int>(active.size()));
      for (size_t j = 0; j < active.size(); ++j) {
        estimate.intrinsics_std(active[j]) = std::sqrt(std::max(0.0, cov_k(j, j)));
      }
    }
    if (options_.estimate_time_offset) {
      estimate.time_offset_std_s = std::sqrt(std::max(0.0, block(&cam.time_offset_s, 1)(0, 0)));
    }
    if (options_.rolling_shutter) {
      estimate.line_delay_std_s = std::sqrt(std::max(0.0, block(&cam.line_delay, 1)(0, 0)));
    }
  }
  for (size_t c = 1; c < cameras_.size(); ++c) BaselineStd(c, cov, offset, result);
  if (target_scale_free_) {
    result->target_scale_std = std::sqrt(std::max(0.0, block(&target_scale_, 1)(0, 0)));
  }
  if (!model_blocks.empty()) ImuModelCovarianceFrom(cov, offset, result);
  if (further_) further_->StdFrom(cov, offset, &result->further_imus);
  const Eigen::VectorXd bias_std = cov.diagonal().tail(6).cwiseMax(0.0).cwiseSqrt();
  result->gyro_bias_std = bias_std.head<3>();
  result->accel_bias_std = bias_std.tail<3>();
  AddStandardDeviationWarnings(options_, imu_noise_->estimate(), result);
}

bool CalibrationProblem::CarryConsideredIntrinsics(std::vector<const double*> wanted,
                                                   const Eigen::MatrixXd& reported_map,
                                                   Eigen::MatrixXd* cov,
                                                   CalibrationResult* result) {
  // Sigma_c: each considered camera's block of the camchain's covariance, its intrinsics rows
  // in the order of the block's tangent (the active entries, ascending); the cameras' blocks
  // are independent (each camchain entry carries its own). The T_cn_cnm1 rows stay with the
  // camera chain's mode.
  std::vector<size_t> considered;
  std::vector<std::vector<int>> rows;  // per considered camera: its tangent's covariance rows
  int num_c = 0;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    if (intrinsics_modes_[c] != ParameterMode::kConsider) continue;
    const CameraCovariance& given = *options_.camchain_covariances[c];
    std::vector<int> r;
    for (int j : camchain_[c].camera.ActiveIntrinsics()) {
      const auto at = std::find(given.intrinsics.begin(), given.intrinsics.end(), j);
      // io/camchain_yaml_covariance.h checks the names against the model's active entries.
      CHECK(at != given.intrinsics.end()) << "cam" << c << ": intrinsic " << j << " not in the "
                                          << "camchain's covariance";
      r.push_back(static_cast<int>(at - given.intrinsics.begin()));
    }
    num_c += static_cast<int>(r.size());
    considered.push_back(c);
    rows.push_back(r);
  }
  if (considered.empty()) return true;
  Eigen::MatrixXd Sigma_c = Eigen::MatrixXd::Zero(num_c, num_c);
  int first = 0;
  for (size_t k = 0; k < considered.size(); ++k) {
    const Eigen::MatrixXd& given = options_.camchain_covariances[considered[k]]->matrix;
    const int n = static_cast<int>(rows[k].size());
    for (int i = 0; i < n; ++i) {
      for (int j = 0; j < n; ++j) Sigma_c(first + i, first + j) = given(rows[k][i], rows[k][j]);
    }
    first += n;
  }
  // The joint covariance of [q; c] from the information with c free and no prior on it: the
  // weights' (no sandwich), whose common scale cancels in S (consider_covariance.h).
  for (size_t c : considered) {
    problem().SetParameterBlockVariable(cameras_[c].intrinsics.data());
    wanted.push_back(cameras_[c].intrinsics.data());
  }
  const int num_q = static_cast<int>(reported_map.rows());
  Eigen::MatrixXd map = Eigen::MatrixXd::Zero(num_q + num_c, reported_map.cols() + num_c);
  map.topLeftCorner(num_q, reported_map.cols()) = reported_map;
  map.bottomRightCorner(num_c, num_c).setIdentity();
  MarginalCovarianceOptions joint_options;
  joint_options.backend = CovarianceBackend::kSchur;
  joint_options.num_threads = options_.solver.num_threads;
  joint_options.reported_map = map;
  const MarginalCovariance joint = ComputeMarginalCovariance(&problem(), wanted, joint_options);
  for (size_t c : considered) problem().SetParameterBlockConstant(cameras_[c].intrinsics.data());
  if (!joint.ok) return false;
  const std::optional<Eigen::MatrixXd> S = ConsiderSensitivity(joint.covariance, num_c);
  if (!S) return false;
  *cov = AddConsidered(*cov, *S, Sigma_c);
  first = 0;
  for (size_t k = 0; k < considered.size(); ++k) {
    const std::vector<int> active = camchain_[considered[k]].camera.ActiveIntrinsics();
    for (size_t j = 0; j < active.size(); ++j, ++first) {
      result->cameras[considered[k]].intrinsics_std(active[j]) =
          std::sqrt(Sigma_c(first, first));
    }
  }
  return true;
}

void CalibrationProblem::ImuModelCovarianceFrom(const Eigen::MatrixXd& cov,
                                                const std::map<const double*, int>& offset,
                                                CalibrationResult* result) {
  // A held entry (estimation/imu_model_observability.h) has no row: the tangent of a block with
  // held entries skips them (ceres::SubsetManifold); a block all held is constant (no offset).
  const std::vector<CovarianceBlock> blocks = ModelCovarianceBlocks(
      spline_->imu_model_kind(), *spline_->imu_model(), [&](const double* block) {
        return spline_->HeldImuModelEntries(block);
      });
  result->imu_model_covariance = CovarianceOfBlocks(cov, offset, blocks);
  result->imu_model_std = ModelStdOf(result->imu_model_covariance);
}

void CalibrationProblem::BaselineStd(size_t c,
                                     const Eigen::MatrixXd& cov,
                                     const std::map<const double*, int>& offset,
                                     CalibrationResult* result) {
  // The baseline |t| of T_cn_cnm1 = T_cn_imu T_cnm1_imu^-1, to first order in the right tangents
  // d = [d_cnm1; d_cn] of the two cameras' extrinsic blocks. With a held chain both cameras use
  // cam0's block (the same d, held T_cn_c0): the baseline is the camchain's, std 0. The gradient
  // by central differences: the baseline is smooth, and steps of 1e-6 (rad, m) give it to about
  // 1e-9 relative, far finer than a std needs.
  double* blocks[2] = {ExtrinsicBlock(c - 1), ExtrinsicBlock(c)};
  const bool shared = blocks[0] == blocks[1];
  auto baseline = [&](const Eigen::Matrix<double, 12, 1>& d) {
    SE3d T[2];
    for (int k = 0; k < 2; ++k) {
      const size_t cam = c - 1 + k;
      const SE3d pose = PoseFromBlock(blocks[k]) * SE3d::Exp(d.segment<6>(shared ? 0 : 6 * k));
      T[k] = HeldToReference(cam) ? options_.camera_chain_T_cn_c0[cam] * pose : pose;
    }
    return (T[1] * T[0].inverse()).translation().norm();
  };
  Eigen::Matrix<double, 12, 12> C = Eigen::Matrix<double, 12, 12>::Zero();
  for (int a = 0; a < (shared ? 1 : 2); ++a) {
    for (int b = 0; b < (shared ? 1 : 2); ++b) {
      C.block<6, 6>(6 * a, 6 * b) = cov.block(offset.at(blocks[a]), offset.at(blocks[b]), 6, 6);
    }
  }
  constexpr double kStep = 1e-6;
  Eigen::Matrix<double, 12, 1> gradient;
  for (int i = 0; i < 12; ++i) {
    Eigen::Matrix<double, 12, 1> d = Eigen::Matrix<double, 12, 1>::Zero();
    d[i] = kStep;
    gradient[i] = (baseline(d) - baseline(-d)) / (2.0 * kStep);
  }
  result->cameras[c].baseline_std_m = std::sqrt(std::max(0.0, gradient.dot(C * gradient)));
}

void CalibrationProblem::Collect(CalibrationResult* result) {
  result->layout = layout_;
  result->trajectory = spline_->trajectory_model();
  // Solved in the target's frame; written in the gravity-aligned world (calibrate.h).
  result->gravity_target = spline_->gravity_w();
  result->T_w_target =
      SE3d(GravityAlignedRotation(result->gravity_target), Eigen::Vector3d::Zero());
  result->gravity_w = result->T_w_target.so3() * result->gravity_target;
  result->control_poses.clear();
  const SE3Splined spline_t = Spline();  // T_t_s
  for (const SE3d& T_t_s : spline_t.control_poses()) {
    result->control_poses.push_back(result->T_w_target * T_t_s);
  }
  result->camchain = camchain_;
  // Kalibr's cam_overlaps: the cameras that saw the target at the same frame time. Without
  // target frames (natural landmarks only) the camchain's own list stays.
  std::map<int64_t, std::set<int>> cameras_at_time;
  for (const TargetFrame& frame : target_frames_) cameras_at_time[frame.t_ns].insert(frame.cam);
  if (!cameras_at_time.empty()) {
    std::vector<std::set<int>> overlaps(cameras_.size());
    for (const auto& [t_ns, cameras] : cameras_at_time) {
      for (int a : cameras) {
        for (int b : cameras) {
          if (a != b) overlaps[a].insert(b);
        }
      }
    }
    for (size_t c = 0; c < cameras_.size(); ++c) {
      result->camchain[c].cam_overlaps.assign(overlaps[c].begin(), overlaps[c].end());
    }
  }
  result->imu_model.model = spline_->imu_model_kind();
  result->imu_model.intrinsics = spline_->imu_model()->Intrinsics();
  if (further_) further_->Collect(*spline_, &result->further_imus);
  result->cameras.resize(cameras_.size());
  result->camera_chain = chain_mode_;
  for (size_t c = 0; c < cameras_.size(); ++c) {
    CameraCalibration& out = result->camchain[c];
    out.T_cam_imu = CameraFromImu(c);
    CameraEstimate& estimate = result->cameras[c];
    if (c > 0) {
      estimate.baseline_m = (out.T_cam_imu * CameraFromImu(c - 1).inverse()).translation().norm();
    }
    estimate.intrinsics_before = camchain_[c].camera.intrinsics();
    estimate.intrinsics_mode = intrinsics_modes_[c];
    if (EstimatesIntrinsics(c)) out.camera.set_intrinsics(cameras_[c].intrinsics);
    estimate.intrinsics_estimated = EstimatesIntrinsics(c);
    if (intrinsics_modes_[c] == ParameterMode::kPrior ||
        intrinsics_modes_[c] == ParameterMode::kConsider) {
      const CameraCovariance& prior = *options_.camchain_covariances[c];
      for (size_t j = 0; j < prior.intrinsics.size(); ++j) {
        estimate.intrinsics_prior_std(prior.intrinsics[j]) = std::sqrt(prior.matrix(j, j));
      }
    }
    out.time_offset_s = cameras_[c].time_offset_s;
    out.line_delay_s = cameras_[c].line_delay;
    result->cameras[c].calibration = out;
    result->cameras[c].time_offset_estimated = options_.estimate_time_offset;
    result->cameras[c].line_delay_estimated = options_.rolling_shutter;
  }
  // IMU residuals.
  const ImuResidualStatistics imu_stats =
      spline_->EvaluateImu(imu_, [&](const ImuSample& s, const ImuPrediction& p) {
        if (options_.keep_residuals) {
          result->imu_samples.push_back(
              {s.t_ns, p.gyro - s.gyro, p.accel - s.accel, p.gyro_bias, p.accel_bias});
        }
      });
  result->num_imu_samples = static_cast<int>(imu_.size());
  result->imu_rate_hz = ImuRateHz(imu_);
  result->gyro_rms = imu_stats.gyro_rms;
  result->accel_rms = imu_stats.accel_rms;
  result->gyro_bias = imu_stats.mean_gyro_bias;
  result->accel_bias = imu_stats.mean_accel_bias;
  // Reprojection residuals (pixels, no weights, no robust loss).
  std::vector<double> cam_sq(cameras_.size(), 0.0);
  std::vector<std::set<std::pair<int64_t, int>>> cam_frames(cameras_.size());
  double all_sq = 0.0;
  int all_count = 0;
  for (const FrameResidual& r : frame_residuals_) {
    const TargetFrame& frame = target_frames_[r.frame];
    std::vector<double> e;
    if (!PixelErrors(r, &e)) continue;
    CameraEstimate& estimate = result->cameras[frame.cam];
    ++estimate.num_frames;
    for (size_t k = 0; k < frame.corners.size(); ++k) {
      const Eigen::Vector2d error(e[2 * k], e[2 * k + 1]);
      cam_sq[frame.cam] += error.squaredNorm();
      all_sq += error.squaredNorm();
      ++all_count;
      ++estimate.num_observations;
      if (options_.keep_residuals) {
        result->reprojection_samples.push_back(
            {frame.t_ns, frame.cam, frame.ids[k], frame.corners[k].uv, error});
      }
    }
  }
  std::set<int> landmarks_used;
  for (const LandmarkResidual& r : landmark_residuals_) {
    const Landmark& landmark = landmarks_[r.landmark];
    const Observation& obs = landmark.others[r.observation];
    std::vector<double> e;
    if (!PixelErrors(r, &e)) continue;
    landmarks_used.insert(r.landmark);
    const Eigen::Vector2d error(e[0], e[1]);
    cam_sq[landmark.cam] += error.squaredNorm();
    all_sq += error.squaredNorm();
    ++all_count;
    ++result->cameras[landmark.cam].num_observations;
    if (options_.keep_residuals) {
      result->reprojection_samples.push_back({obs.t_ns, obs.cam_id, landmark.id, obs.uv, error});
    }
  }
  result->num_landmarks = static_cast<int>(landmarks_used.size());
  for (size_t c = 0; c < cameras_.size(); ++c) {
    const int count = result->cameras[c].num_observations;
    result->cameras[c].reprojection_rms_px = count > 0 ? std::sqrt(cam_sq[c] / count) : 0.0;
  }
  result->reprojection_rms_px = all_count > 0 ? std::sqrt(all_sq / all_count) : 0.0;
  std::sort(result->reprojection_samples.begin(),
            result->reprojection_samples.end(),
            [](const ReprojectionSample& a, const ReprojectionSample& b) {
              return std::tie(a.t_ns, a.cam_id, a.point_id) <
                     std::tie(b.t_ns, b.cam_id, b.point_id);
            });
}

}  // namespace internal
}  // namespace splinecal
