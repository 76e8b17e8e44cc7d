#include "splinecal/estimation/spline_problem.h"

#include <ceres/ceres.h>
#include <glog/logging.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include "splinecal/error.h"
#include "splinecal/estimation/bias_costs.h"
#include "splinecal/estimation/detail/imu_costs.h"
#include "splinecal/estimation/detail/imu_model_costs.h"
#include "splinecal/imu/imu_intrinsic_model.h"
#include "splinecal/imu/spline_body_motion.h"

namespace splinecal {

SplineProblem::SplineProblem(const KnotLayout& layout,
                             const std::vector<SE3d>& control_poses,
                             const BiasSpline& bias,
                             const ResidualOptions& options,
                             TrajectoryModel trajectory)
    : layout_(layout), bias_(bias), options_(options), trajectory_(trajectory) {
  if (!layout_.valid()) {
    throw Error("SplineProblem: needs at least 4 control poses and a positive knot spacing");
  }
  if (static_cast<int>(control_poses.size()) != layout_.num_control_poses) {
    throw Error("SplineProblem: the layout has " + std::to_string(layout_.num_control_poses) +
                " control poses, the initial guess " + std::to_string(control_poses.size()));
  }
  const int n = layout_.num_control_poses;
  control_values_.resize(kPoseBlockSize * static_cast<size_t>(n));
  control_blocks_.resize(n);
  for (int i = 0; i < n; ++i) {
    control_blocks_[i] = &control_values_[kPoseBlockSize * i];
    PoseToBlock(control_poses[i], control_blocks_[i]);
  }
  gyro_bias_values_.assign(3 * static_cast<size_t>(bias_.num_points()), 0.0);
  accel_bias_values_.assign(3 * static_cast<size_t>(bias_.num_points()), 0.0);
  CHECK_EQ(static_cast<bool>(options_.replacement.gyro),
           static_cast<bool>(options_.replacement.accel))
      << "ReplacementCosts: gyro and accel go together";
  if (!options_.replacement.gyro && options_.share_knot_caches) {
    callback_ =
        std::make_unique<SplineEvaluationCallback>(control_blocks_, layout_.t0_ns, layout_.dt_ns);
  }
  Reset();
}

SplineProblem::~SplineProblem() = default;

std::vector<SE3d> SplineProblem::ControlPoses() const {
  std::vector<SE3d> poses(control_blocks_.size());
  for (size_t i = 0; i < poses.size(); ++i) poses[i] = PoseFromBlock(control_blocks_[i]);
  return poses;
}

void SplineProblem::SetControlPoses(const std::vector<SE3d>& control_poses) {
  if (control_poses.size() != control_blocks_.size()) {
    throw Error("SplineProblem::SetControlPoses: expected " +
                std::to_string(control_blocks_.size()) + " control poses, got " +
                std::to_string(control_poses.size()));
  }
  for (size_t i = 0; i < control_poses.size(); ++i)
    PoseToBlock(control_poses[i], control_blocks_[i]);
  if (callback_) callback_->Update();
}

SE3Splined SplineProblem::Spline() const {
  return SE3Splined(ControlPoses(), layout_.t0_ns, layout_.dt_ns, trajectory_);
}

void SplineProblem::SetBiases(const Eigen::Vector3d& gyro_bias, const Eigen::Vector3d& accel_bias) {
  for (int m = 0; m < bias_.num_points(); ++m) {
    Eigen::Map<Eigen::Vector3d>(this->gyro_bias(m)) = gyro_bias;
    Eigen::Map<Eigen::Vector3d>(this->accel_bias(m)) = accel_bias;
  }
}

void SplineProblem::SetGravity(const Eigen::Vector3d& g_w) {
  for (int a = 0; a < 3; ++a) gravity_[a] = g_w[a];
}

Eigen::Vector3d SplineProblem::GyroBiasAt(int64_t t_ns) const {
  return bias_.Evaluate(gyro_bias_values_.data(), t_ns);
}

Eigen::Vector3d SplineProblem::AccelBiasAt(int64_t t_ns) const {
  return bias_.Evaluate(accel_bias_values_.data(), t_ns);
}

ceres::Problem& SplineProblem::Reset(bool hold_first_pose) {
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.evaluation_callback = callback_.get();
  problem_ = std::make_unique<ceres::Problem>(problem_options);
  kinds_.clear();
  for (double* block : control_blocks_) {
    problem_->AddParameterBlock(block, kPoseBlockSize, &se3_manifold_);
  }
  if (hold_first_pose) problem_->SetParameterBlockConstant(control_blocks_[0]);
  for (int m = 0; m < bias_.num_points(); ++m) {
    problem_->AddParameterBlock(gyro_bias(m), 3);
    problem_->AddParameterBlock(accel_bias(m), 3);
  }
  problem_->AddParameterBlock(gravity_.data(), 3, &gravity_manifold_);
  held_model_manifolds_.clear();
  for (double* block : ImuModelBlocks()) {
    const int size = block == imu_model_.a.data() ? kFullMatrixParameters
                     : block == imu_model_.m_a.data() || block == imu_model_.m_g.data()
                         ? kLowerTriangularParameters
                         : 3;
    problem_->AddParameterBlock(block, size);
    const std::vector<int> held = HeldImuModelEntries(block);
    if (static_cast<int>(held.size()) == size) {
      problem_->SetParameterBlockConstant(block);
    } else if (!held.empty()) {
      held_model_manifolds_.push_back(std::make_unique<ceres::SubsetManifold>(size, held));
      problem_->SetManifold(block, held_model_manifolds_.back().get());
    }
  }
  return *problem_;
}

void SplineProblem::HoldImuModelEntry(double* block, int index) {
  const ImuModelParameters nominal;
  const std::pair<const double*, const double*> blocks[] = {
      {imu_model_.m_a.data(), nominal.m_a.data()},   {imu_model_.m_g.data(), nominal.m_g.data()},
      {imu_model_.a.data(), nominal.a.data()},       {imu_model_.phi_gyro_i.data(), nominal.phi_gyro_i.data()},
      {imu_model_.ry_i.data(), nominal.ry_i.data()}, {imu_model_.rz_i.data(), nominal.rz_i.data()}};
  for (const auto& [values, nominal_values] : blocks) {
    if (values == block) block[index] = nominal_values[index];
  }
  std::vector<int>& held = held_model_entries_[block];
  if (std::find(held.begin(), held.end(), index) == held.end()) {
    held.push_back(index);
    std::sort(held.begin(), held.end());
  }
}

std::vector<int> SplineProblem::HeldImuModelEntries(const double* block) const {
  const auto it = held_model_entries_.find(block);
  return it == held_model_entries_.end() ? std::vector<int>() : it->second;
}

std::vector<double*> SplineProblem::ImuModelBlocks() {
  if (imu_model_kind_ == ImuModelKind::kCalibrated) return {};
  std::vector<double*> blocks = {imu_model_.m_a.data(), imu_model_.m_g.data(),
                                 imu_model_.a.data(), imu_model_.phi_gyro_i.data()};
  if (imu_model_kind_ == ImuModelKind::kScaleMisalignmentSizeEffect) {
    blocks.insert(blocks.end(), {imu_model_.ry_i.data(), imu_model_.rz_i.data()});
  }
  return blocks;
}

void SplineProblem::AddImuResiduals(const std::vector<ImuSample>& imu,
                                    double sigma_gyro,
                                    double sigma_accel) {
  const int nb = bias_.points_per_segment();
  const bool analytic = !options_.replacement.gyro;
  const double dt_s = layout_.dt_s();
  const double duration_s =
      imu.size() > 1 ? 1e-9 * static_cast<double>(imu.back().t_ns - imu.front().t_ns) : 0.0;
  const double rate_hz = duration_s > 0.0 ? static_cast<double>(imu.size() - 1) / duration_s : 0.0;
  size_t k = 0;
  while (k < imu.size()) {
    SegmentPosition position;
    if (!layout_.SegmentAtNs(imu[k].t_ns, &position)) {
      throw Error("SplineProblem: IMU sample at " + std::to_string(imu[k].t_ns) +
                  " ns is outside the spline's valid range");
    }
    const int index = position.index;
    const int bias_segment = bias_.SegmentOfPoseSegment(index);
    ImuResidualSegment gyro_segment;
    gyro_segment.segment_index = index;
    gyro_segment.dt_s = dt_s;
    gyro_segment.sigma = sigma_gyro;
    gyro_segment.model = trajectory_;
    gyro_segment.shared = callback_.get();
    ImuResidualSegment accel_segment = gyro_segment;
    accel_segment.sigma = sigma_accel;
    std::vector<ImuResidualSample> gyro_samples;
    std::vector<ImuResidualSample> accel_samples;
    const size_t expected = static_cast<size_t>(dt_s * rate_hz) + 2;
    gyro_samples.reserve(expected);
    accel_samples.reserve(expected);
    for (; k < imu.size(); ++k) {
      if (!layout_.SegmentAtNs(imu[k].t_ns, &position) || position.index != index) break;
      ImuResidualSample sample;
      sample.u = position.u;
      sample.bias_weights = bias_.WeightsInSegment(imu[k].t_ns, bias_segment).weights;
      sample.measured = imu[k].gyro;
      gyro_samples.push_back(sample);
      sample.measured = imu[k].accel;
      accel_samples.push_back(sample);
    }
    std::vector<double*> gyro_blocks(control_blocks_.begin() + (index - 1),
                                     control_blocks_.begin() + (index + 3));
    std::vector<double*> accel_blocks = gyro_blocks;
    const int first_bias = nb == 1 ? 0 : bias_segment - 1;
    for (int j = 0; j < nb; ++j) {
      gyro_blocks.push_back(gyro_bias(first_bias + j));
      accel_blocks.push_back(accel_bias(first_bias + j));
    }
    accel_blocks.push_back(gravity_.data());

    if (imu_model_kind_ != ImuModelKind::kCalibrated) {
      // Kalibr's model (estimation/detail/imu_model_costs.h): the gyro reads f_b through A, so it takes
      // gravity too.
      const std::vector<double*> model = ImuModelBlocks();
      gyro_blocks.push_back(gravity_.data());
      gyro_blocks.insert(gyro_blocks.end(), model.begin() + 1, model.begin() + 4);
      accel_blocks.push_back(model[0]);
      accel_blocks.insert(accel_blocks.end(), model.begin() + 4, model.end());
      ImuModelSegment gyro_model{imu_model_kind_, gyro_segment, std::move(gyro_samples), nb};
      ImuModelSegment accel_model{imu_model_kind_, accel_segment, std::move(accel_samples), nb};
      kinds_[problem_->AddResidualBlock(NewImuModelGyroCost(gyro_model), nullptr, gyro_blocks)] =
          ImuResidualKind::kGyro;
      kinds_[problem_->AddResidualBlock(
          NewImuModelAccelCost(accel_model), nullptr, accel_blocks)] = ImuResidualKind::kAccel;
    } else if (!analytic) {
      for (size_t s = 0; s < gyro_samples.size(); ++s) {
        kinds_[problem_->AddResidualBlock(
            options_.replacement.gyro(nb, gyro_segment, gyro_samples[s]), nullptr, gyro_blocks)] =
            ImuResidualKind::kGyro;
        kinds_[problem_->AddResidualBlock(options_.replacement.accel(
                                              nb, accel_segment, accel_samples[s]),
                                          nullptr,
                                          accel_blocks)] = ImuResidualKind::kAccel;
      }
    } else if (options_.layout == ImuResidualLayout::kPerSample) {
      for (size_t s = 0; s < gyro_samples.size(); ++s) {
        ceres::CostFunction* gyro_cost;
        ceres::CostFunction* accel_cost;
        if (nb == 1) {
          gyro_cost = new GyroCostFunction<1>(gyro_segment, gyro_samples[s]);
          accel_cost = new AccelCostFunction<1>(accel_segment, accel_samples[s]);
        } else {
          gyro_cost = new GyroCostFunction<4>(gyro_segment, gyro_samples[s]);
          accel_cost = new AccelCostFunction<4>(accel_segment, accel_samples[s]);
        }
        kinds_[problem_->AddResidualBlock(gyro_cost, nullptr, gyro_blocks)] =
            ImuResidualKind::kGyro;
        kinds_[problem_->AddResidualBlock(accel_cost, nullptr, accel_blocks)] =
            ImuResidualKind::kAccel;
      }
    } else {
      ceres::CostFunction* gyro_cost;
      ceres::CostFunction* accel_cost;
      if (nb == 1) {
        gyro_cost = new GyroSegmentCostFunction<1>(gyro_segment, std::move(gyro_samples));
        accel_cost = new AccelSegmentCostFunction<1>(accel_segment, std::move(accel_samples));
      } else {
        gyro_cost = new GyroSegmentCostFunction<4>(gyro_segment, std::move(gyro_samples));
        accel_cost = new AccelSegmentCostFunction<4>(accel_segment, std::move(accel_samples));
      }
      kinds_[problem_->AddResidualBlock(gyro_cost, nullptr, gyro_blocks)] =
          ImuResidualKind::kGyro;
      kinds_[problem_->AddResidualBlock(accel_cost, nullptr, accel_blocks)] =
          ImuResidualKind::kAccel;
    }
  }
}

void SplineProblem::AddBiasRandomWalkResiduals(const ImuNoise& noise) {
  if (bias_.is_constant()) return;
  const double db = bias_.dt_s();
  for (int m = 1; m + 2 < bias_.num_points(); ++m) {
    kinds_[problem_->AddResidualBlock(
        new BiasRandomWalkCostFunction(db, noise.gyroscope_random_walk),
        nullptr,
        {gyro_bias(m - 1), gyro_bias(m), gyro_bias(m + 1), gyro_bias(m + 2)})] =
        ImuResidualKind::kGyroRandomWalk;
    kinds_[problem_->AddResidualBlock(
        new BiasRandomWalkCostFunction(db, noise.accelerometer_random_walk),
        nullptr,
        {accel_bias(m - 1), accel_bias(m), accel_bias(m + 1), accel_bias(m + 2)})] =
        ImuResidualKind::kAccelRandomWalk;
  }
}

ImuResidualKind SplineProblem::ResidualKind(ceres::ResidualBlockId id) const {
  const auto it = kinds_.find(id);
  return it == kinds_.end() ? ImuResidualKind::kNotImu : it->second;
}

int SplineProblem::TimeWindowOf(ceres::ResidualBlockId id, double window_s) const {
  std::vector<double*> blocks;
  problem_->GetParameterBlocksForResidualBlock(id, &blocks);
  auto index_in = [](const std::vector<double>& values, int stride, const double* block) {
    if (values.empty() || block < values.data() || block >= values.data() + values.size()) {
      return -1;
    }
    return static_cast<int>((block - values.data()) / stride);
  };
  for (const double* block : blocks) {
    double t_s = -1.0;
    const int pose = index_in(control_values_, kPoseBlockSize, block);
    if (pose >= 0) t_s = pose * layout_.dt_s();
    int bias = index_in(gyro_bias_values_, 3, block);
    if (bias < 0) bias = index_in(accel_bias_values_, 3, block);
    if (pose < 0 && bias >= 0) {
      t_s = bias_.is_constant() ? -1.0 : 1e-9 * static_cast<double>(bias_.t0_ns() - layout_.t0_ns) +
                                              bias * bias_.dt_s();
    }
    if (t_s >= 0.0) return static_cast<int>(t_s / window_s);
  }
  return 0;
}

ImuResidualStatistics SplineProblem::EvaluateImu(
    const std::vector<ImuSample>& imu,
    const std::function<void(const ImuSample&, const ImuPrediction&)>& visit) const {
  ImuResidualStatistics stats;
  if (imu.empty()) return stats;
  const SE3Splined spline = Spline();
  const Eigen::Vector3d g_w = gravity_w();
  const ImuIntrinsicsd intrinsics = imu_model_.Intrinsics();
  double gyro_sq = 0.0;
  double accel_sq = 0.0;
  for (const ImuSample& s : imu) {
    ImuPrediction p;
    p.gyro_bias = GyroBiasAt(s.t_ns);
    p.accel_bias = AccelBiasAt(s.t_ns);
    if (imu_model_kind_ == ImuModelKind::kCalibrated) {
      PredictImu<double>(
          spline, spline.SegmentAtNs(s.t_ns), g_w, p.gyro_bias, p.accel_bias, &p.gyro, &p.accel);
    } else {
      PredictImuReadings<double>(imu_model_kind_, intrinsics,
                                 SplineBodyMotion(spline, spline.SegmentAtNs(s.t_ns), g_w),
                                 p.gyro_bias, p.accel_bias, &p.gyro, &p.accel);
    }
    gyro_sq += (p.gyro - s.gyro).squaredNorm();
    accel_sq += (p.accel - s.accel).squaredNorm();
    stats.mean_gyro_bias += p.gyro_bias;
    stats.mean_accel_bias += p.accel_bias;
    if (visit) visit(s, p);
  }
  const double n = static_cast<double>(imu.size());
  stats.gyro_rms = std::sqrt(gyro_sq / (3.0 * n));
  stats.accel_rms = std::sqrt(accel_sq / (3.0 * n));
  stats.mean_gyro_bias /= n;
  stats.mean_accel_bias /= n;
  return stats;
}

Eigen::MatrixXd SplineProblem::MeanBiasMap(const std::vector<ImuSample>& imu) const {
  const int points = bias_.num_points();
  const std::vector<double> weights = MeanBiasWeights(imu);
  Eigen::MatrixXd map = Eigen::MatrixXd::Zero(6, 6 * points);
  for (int m = 0; m < points; ++m) {
    map.block<3, 3>(0, 3 * m) = weights[m] * Eigen::Matrix3d::Identity();
    map.block<3, 3>(3, 3 * (points + m)) = weights[m] * Eigen::Matrix3d::Identity();
  }
  return map;
}

std::vector<double> SplineProblem::MeanBiasWeights(const std::vector<ImuSample>& imu) const {
  std::vector<double> a(bias_.num_points(), 0.0);
  if (bias_.is_constant()) {
    a[0] = 1.0;
    return a;
  }
  for (const ImuSample& s : imu) {
    const BiasWeights w = bias_.WeightsAt(s.t_ns);
    for (int j = 0; j < 4; ++j)
      a[w.first_point + j] += w.weights[j] / static_cast<double>(imu.size());
  }
  return a;
}

}  // namespace splinecal
