#include "further_imus.h"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>
#include <numeric>

#include "imu_covariance_rows.h"
#include "splinecal/error.h"
#include "splinecal/estimation/imu_model_observability.h"
#include "splinecal/estimation/interval_manifold.h"
#include "splinecal/imu/imu_rate.h"
#include "splinecal/imu/rigid_body_point.h"
#include "splinecal/imu/spline_body_motion.h"
#include "splinecal/io/poses.h"
#include "splinecal/lie/so3.h"
#include "splinecal/string_printf.h"
#include "splinecal/units.h"
#include "splinecal/vio/time_offset_correlation.h"

namespace splinecal {
namespace internal {
namespace {

// Rate of the reference spline's poses handed to the gyro-rate correlation [Hz]: well above the
// motion's bandwidth (periods >= 0.8 s in the tests, a few Hz on hand-held rigs).
constexpr double kCorrelationPoseRateHz = 100.0;
// A further IMU's rate may differ from the reference's by this fraction (clock drift, not
// another configuration).
constexpr double kMaxRateMismatch = 0.01;

double NaN() { return std::numeric_limits<double>::quiet_NaN(); }

// The time, in seconds since the layout's t0, of a stamp shifted by an offset.
int64_t ShiftedNs(int64_t t_ns, double offset_s) { return t_ns + std::llround(offset_s * 1e9); }

// C minimising sum_k |x_k - C y_k|^2 over rotations (Kabsch): C = U diag(1, 1, det) V^T from
// the SVD of sum_k x_k y_k^T.
Eigen::Matrix3d KabschRotation(const Eigen::Matrix3d& sum_x_yT) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(sum_x_yT, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

}  // namespace

void CheckFurtherImus(const std::vector<FurtherImu>& imus, double reference_rate_hz) {
  for (size_t i = 0; i < imus.size(); ++i) {
    const FurtherImu& imu = imus[i];
    const std::string name = "IMU " + std::to_string(i + 1) + " (" + imu.name + ")";
    if (imu.samples.size() < 2) throw Error("calibrate: " + name + " has fewer than 2 samples");
    for (size_t k = 1; k < imu.samples.size(); ++k) {
      if (imu.samples[k].t_ns <= imu.samples[k - 1].t_ns) {
        throw Error("calibrate: " + name + ": timestamps not increasing at sample " +
                    std::to_string(k));
      }
    }
    const double rate = ImuRateHz(imu.samples);
    if (std::abs(rate / reference_rate_hz - 1.0) > kMaxRateMismatch) {
      throw Error(StringPrintf(
          "calibrate: %s samples at %.6g Hz, the reference IMU at %.6g Hz: every IMU must have "
          "the reference's rate (resample it first)",
          name.c_str(), rate, reference_rate_hz));
    }
  }
}

FurtherImus::FurtherImus(const std::vector<FurtherImu>& imus,
                         const KnotLayout& layout,
                         const BiasSpline& bias,
                         TrajectoryModel model,
                         double max_time_offset_s)
    : layout_(layout), bias_(bias), model_(model), max_time_offset_s_(max_time_offset_s) {
  time_offset_manifold_ = std::make_shared<IntervalManifold>(-max_time_offset_s, max_time_offset_s);
  const int64_t margin_ns = std::llround(max_time_offset_s * 1e9) + 1;
  for (size_t i = 0; i < imus.size(); ++i) {
    State state;
    state.name = imus[i].name;
    state.noise = imus[i].noise;
    state.kind = imus[i].model;
    state.rate_hz = ImuRateHz(imus[i].samples);
    // Kalibr's densities: per-sample std = density sqrt(rate) (docs/conventions.md).
    state.sigma_gyro = state.noise.gyroscope_noise_density * std::sqrt(state.rate_hz);
    state.sigma_accel = state.noise.accelerometer_noise_density * std::sqrt(state.rate_hz);
    for (const ImuSample& s : imus[i].samples) {
      if (s.t_ns - margin_ns >= layout.start_time_ns() && s.t_ns + margin_ns <= layout.end_time_ns()) {
        state.samples.push_back(s);
      }
    }
    if (state.samples.size() < 10) {
      throw Error("calibrate: IMU " + std::to_string(i + 1) + " (" + state.name +
                  ") has fewer than 10 samples during the frames: another recording?");
    }
    state.gyro_bias.assign(3 * bias.num_points(), 0.0);
    state.accel_bias.assign(3 * bias.num_points(), 0.0);
    imus_.push_back(std::move(state));
  }
}

void FurtherImus::Initialise(const SE3Splined& spline,
                             const Eigen::Vector3d& g_w,
                             std::vector<std::string>* warnings) {
  // The reference spline's poses as the "pose source" of the correlation.
  std::vector<StampedPose> poses;
  const int64_t step_ns = std::llround(1e9 / kCorrelationPoseRateHz);
  for (int64_t t = spline.start_time_ns(); t <= spline.end_time_ns(); t += step_ns) {
    const SE3d T_w_b = spline.PoseNs(t);
    poses.push_back({t, T_w_b.translation(), T_w_b.so3().quaternion()});
  }
  for (size_t i = 0; i < imus_.size(); ++i) {
    State& imu = imus_[i];
    // t_stamp = t_reference + offset (vio/time_offset_correlation.h) = t_reference - time_offset.
    double offset = 0.0;
    bool at_edge = false;
    if (EstimateTimeOffsetByCorrelation(imu.samples, poses, 0.0, max_time_offset_s_, &offset,
                                        &at_edge) &&
        !at_edge) {
      imu.time_offset_s = -offset;
    } else {
      imu.time_offset_s = 0.0;
      warnings->push_back("IMU " + std::to_string(i + 1) + " (" + imu.name +
                          "): the gyro-rate correlation found no time offset within " +
                          StringPrintf("%.3g", max_time_offset_s_) + " s; starting at 0");
    }
    imu.initial_time_offset_s = imu.time_offset_s;
    // C_i_b: gyro_k - b_g = C_i_b w_b(t_k + time_offset), both centred (the bias drops out).
    std::vector<BodyMotion<double>> motion;
    Eigen::Vector3d mean_x = Eigen::Vector3d::Zero();
    Eigen::Vector3d mean_y = Eigen::Vector3d::Zero();
    for (const ImuSample& s : imu.samples) {
      const Segment<double> seg = spline.SegmentAtNs(ShiftedNs(s.t_ns, imu.time_offset_s));
      motion.push_back(SplineBodyMotion(spline, seg, g_w));
      mean_x += s.gyro;
      mean_y += motion.back().w_b;
    }
    const double n = static_cast<double>(imu.samples.size());
    mean_x /= n;
    mean_y /= n;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    for (size_t k = 0; k < motion.size(); ++k) {
      H += (imu.samples[k].gyro - mean_x) * (motion[k].w_b - mean_y).transpose();
    }
    const Eigen::Matrix3d C = KabschRotation(H);
    imu.initial_C_i_b = C;
    RotationToBlock(SO3d::FromMatrix(C), imu.q_i_b.data());
    imu.r_b.setZero();
    // Constant biases: the mean residuals at r_b = 0.
    Eigen::Vector3d b_g = Eigen::Vector3d::Zero();
    Eigen::Vector3d b_a = Eigen::Vector3d::Zero();
    for (size_t k = 0; k < motion.size(); ++k) {
      b_g += imu.samples[k].gyro - C * motion[k].w_b;
      b_a += imu.samples[k].accel - C * motion[k].f_b;
    }
    for (int m = 0; m < bias_.num_points(); ++m) {
      Eigen::Map<Eigen::Vector3d>(&imu.gyro_bias[3 * m]) = b_g / n;
      Eigen::Map<Eigen::Vector3d>(&imu.accel_bias[3 * m]) = b_a / n;
    }
  }
}

void FurtherImus::HoldUndeterminedLeverArms(const SE3Splined& spline,
                                            double max_std_m,
                                            std::vector<std::string>* warnings) {
  const Eigen::Vector3d g_w = Eigen::Vector3d::Zero();  // the lever-arm Jacobian ignores f_b
  for (size_t i = 0; i < imus_.size(); ++i) {
    State& imu = imus_[i];
    // The information of r_b from the accelerometer alone (rigid_body_point.h: d accel / d r_b =
    // C_i_b ([dw_b]x + [w_b]x^2)); its weakest direction's std. Correlations with the biases and
    // the rest are ignored: a guard against no rotation, not the reported std.
    const Eigen::Matrix3d C = RotationFromBlock(imu.q_i_b.data()).matrix();
    Eigen::Matrix3d info = Eigen::Matrix3d::Zero();
    for (const ImuSample& s : imu.samples) {
      const BodyMotion<double> m =
          SplineBodyMotion(spline, spline.SegmentAtNs(ShiftedNs(s.t_ns, imu.time_offset_s)), g_w);
      const Eigen::Matrix3d J = C * LeverArmJacobian(m.w_b, m.dw_b) / imu.sigma_accel;
      info += J.transpose() * J;
    }
    const double weakest = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(info).eigenvalues()(0);
    const double std_m = weakest > 0.0 ? 1.0 / std::sqrt(weakest) : std::numeric_limits<double>::infinity();
    if (std_m <= max_std_m) continue;
    imu.lever_arm_held = true;
    imu.r_b.setZero();
    warnings->push_back(StringPrintf(
        "IMU %zu (%s): its lever arm r_b is not determined (std %.3g m in its weakest direction, "
        "above %.3g m: too little rotation); held at 0",
        i + 1, imu.name.c_str(), std_m, max_std_m));
  }
}

void FurtherImus::HoldUndeterminedModelParameters(SplineProblem* spline,
                                                  std::vector<std::string>* warnings) {
  for (size_t i = 0; i < imus_.size(); ++i) {
    State& imu = imus_[i];
    std::vector<ImuModelParameter> parameters = ListImuModelParameters(imu.kind, &imu.model);
    if (parameters.empty()) continue;
    const std::vector<double*> model = ModelBlocks(&imu);
    // The information of the model's blocks from this IMU's residuals alone, all else held: a
    // lower bound of their stds (estimation/imu_model_observability.h).
    std::vector<int> sizes;
    Eigen::MatrixXd information;
    for (const FurtherImuSegment& segment : Segments(imu)) {
      const std::unique_ptr<ceres::CostFunction> cost(NewFurtherImuCost(segment));
      std::vector<double*> blocks =
          Blocks(&imu, segment, spline->control_blocks(), spline->gravity());
      const size_t first = blocks.size() - model.size();
      const std::vector<int32_t>& block_sizes = cost->parameter_block_sizes();
      if (sizes.empty()) {
        sizes.assign(block_sizes.begin() + first, block_sizes.end());
        const int columns = std::accumulate(sizes.begin(), sizes.end(), 0);
        information = Eigen::MatrixXd::Zero(columns, columns);
      }
      const int rows = cost->num_residuals();
      using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
      std::vector<RowMajor> J(blocks.size());
      std::vector<double*> jacobians(blocks.size(), nullptr);
      for (size_t b = first; b < blocks.size(); ++b) {
        J[b].resize(rows, block_sizes[b]);
        jacobians[b] = J[b].data();
      }
      Eigen::VectorXd residuals(rows);
      cost->Evaluate(blocks.data(), residuals.data(), jacobians.data());
      Eigen::MatrixXd J_model(rows, information.cols());
      for (size_t b = first, column = 0; b < blocks.size(); column += J[b].cols(), ++b) {
        J_model.middleCols(column, J[b].cols()) = J[b];
      }
      information.noalias() += J_model.transpose() * J_model;
    }
    SetLowerBoundStds(information, model, sizes, &parameters);
    std::vector<ImuModelParameter> undetermined;
    for (const ImuModelParameter& p : parameters) {
      if (!(p.lower_bound_std <= p.meaningless_std)) undetermined.push_back(p);
    }
    if (undetermined.empty()) continue;
    State nominal_state;  // its model blocks at nominal, in ModelBlocks' order
    nominal_state.kind = imu.kind;
    const std::vector<double*> nominal = ModelBlocks(&nominal_state);
    for (const ImuModelParameter& p : undetermined) {
      const size_t b = std::find(model.begin(), model.end(), p.block) - model.begin();
      p.block[p.index] = nominal[b][p.index];
      std::vector<int>& held = imu.held_model[p.block];
      held.push_back(p.index);
      std::sort(held.begin(), held.end());
    }
    warnings->push_back(StringPrintf("IMU %zu (%s): ", i + 1, imu.name.c_str()) +
                        UndeterminedImuModelWarning(undetermined));
  }
}

std::vector<FurtherImuSegment> FurtherImus::Segments(const State& imu) const {
  std::vector<FurtherImuSegment> segments;
  const double dt_s = layout_.dt_s();
  for (const ImuSample& s : imu.samples) {
    const int64_t t_ns = ShiftedNs(s.t_ns, imu.time_offset_s);
    const int index = layout_.ClampedSegmentAtNs(t_ns);
    if (segments.empty() || segments.back().segment_index != index) {
      FurtherImuSegment segment;
      segment.segment_index = index;
      segment.dt_s = dt_s;
      segment.model = model_;
      segment.kind = imu.kind;
      segment.sigma_gyro = imu.sigma_gyro;
      segment.sigma_accel = imu.sigma_accel;
      segment.bias_blocks = bias_.points_per_segment();
      segments.push_back(segment);
    }
    FurtherImuSample sample;
    // u at time offset 0 (the cost adds time_offset / dt).
    sample.u0 = 1e-9 * static_cast<double>(s.t_ns - layout_.knot_time_ns(index)) / dt_s;
    sample.gyro = s.gyro;
    sample.accel = s.accel;
    sample.bias_weights =
        bias_.WeightsInSegment(t_ns, bias_.SegmentOfPoseSegment(index)).weights;
    segments.back().samples.push_back(sample);
  }
  return segments;
}

std::vector<double*> FurtherImus::Blocks(State* imu,
                                         const FurtherImuSegment& segment,
                                         const std::vector<double*>& control_blocks,
                                         double* gravity) const {
  std::vector<double*> blocks(control_blocks.begin() + (segment.segment_index - 1),
                              control_blocks.begin() + (segment.segment_index + 3));
  const int nb = segment.bias_blocks;
  const int first = nb == 1 ? 0 : bias_.SegmentOfPoseSegment(segment.segment_index) - 1;
  for (int j = 0; j < nb; ++j) blocks.push_back(&imu->gyro_bias[3 * (first + j)]);
  for (int j = 0; j < nb; ++j) blocks.push_back(&imu->accel_bias[3 * (first + j)]);
  blocks.insert(blocks.end(), {gravity, imu->q_i_b.data(), imu->r_b.data(), &imu->time_offset_s});
  const std::vector<double*> model = ModelBlocks(imu);
  blocks.insert(blocks.end(), model.begin(), model.end());
  return blocks;
}

std::vector<double*> FurtherImus::ModelBlocks(State* imu) {
  ImuModelParameters& p = imu->model;
  std::vector<double*> blocks;
  if (imu->kind == ImuModelKind::kCalibrated) return blocks;
  blocks = {p.m_a.data(), p.m_g.data(), p.a.data(), p.phi_gyro_i.data()};
  if (imu->kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
    blocks.insert(blocks.end(), {p.ry_i.data(), p.rz_i.data()});
  }
  return blocks;
}

void FurtherImus::AddToProblem(SplineProblem* spline) {
  ceres::Problem& problem = spline->problem();
  held_manifolds_.clear();
  for (State& imu : imus_) {
    imu.built_time_offset_s = imu.time_offset_s;
    problem.AddParameterBlock(imu.q_i_b.data(), kRotationBlockSize, &so3_manifold_);
    problem.AddParameterBlock(imu.r_b.data(), 3);
    if (imu.lever_arm_held) problem.SetParameterBlockConstant(imu.r_b.data());
    problem.AddParameterBlock(&imu.time_offset_s, 1, time_offset_manifold_.get());
    for (const FurtherImuSegment& segment : Segments(imu)) {
      problem.AddResidualBlock(NewFurtherImuCost(segment), nullptr,
                               Blocks(&imu, segment, spline->control_blocks(), spline->gravity()));
    }
    for (const auto& [block, held] : imu.held_model) {
      double* values = const_cast<double*>(block);
      const int size = problem.ParameterBlockSize(values);
      if (static_cast<int>(held.size()) == size) {
        problem.SetParameterBlockConstant(values);
      } else {
        held_manifolds_.push_back(std::make_unique<ceres::SubsetManifold>(size, held));
        problem.SetManifold(values, held_manifolds_.back().get());
      }
    }
    if (bias_.is_constant()) continue;
    // This IMU's own bias random walk, with its own densities (estimation/bias_costs.h).
    const double db = bias_.dt_s();
    for (int m = 1; m + 2 < bias_.num_points(); ++m) {
      for (auto [values, density] :
           {std::pair{&imu.gyro_bias, imu.noise.gyroscope_random_walk},
            std::pair{&imu.accel_bias, imu.noise.accelerometer_random_walk}}) {
        problem.AddResidualBlock(new BiasRandomWalkCostFunction(db, density), nullptr,
                                 {&(*values)[3 * (m - 1)], &(*values)[3 * m],
                                  &(*values)[3 * (m + 1)], &(*values)[3 * (m + 2)]});
      }
    }
  }
}

bool FurtherImus::NeedRebuild() const {
  for (const State& imu : imus_) {
    if (std::abs(imu.time_offset_s - imu.built_time_offset_s) >
        kFurtherImuRebuildFraction * layout_.dt_s()) {
      return true;
    }
  }
  return false;
}

void FurtherImus::AddCovarianceBlocks(ceres::Problem* problem,
                                      std::vector<const double*>* wanted,
                                      std::map<const double*, int>* offset,
                                      int* rows) const {
  for (State& imu : imus_) {
    std::vector<double*> blocks = {imu.q_i_b.data(), imu.r_b.data(), &imu.time_offset_s};
    const std::vector<double*> model = ModelBlocks(&imu);
    blocks.insert(blocks.end(), model.begin(), model.end());
    for (const double* block : blocks) {
      if (problem->IsParameterBlockConstant(const_cast<double*>(block))) continue;
      (*offset)[block] = *rows;
      wanted->push_back(block);
      *rows += problem->ParameterBlockTangentSize(block);
    }
  }
}

void FurtherImus::Collect(const SplineProblem& spline, std::vector<FurtherImuEstimate>* out) const {
  out->clear();
  Eigen::Vector3d g_w = spline.gravity_w();
  for (State& imu : imus_) {
    FurtherImuEstimate e;
    e.name = imu.name;
    e.calibration.model = imu.kind;
    e.calibration.intrinsics = ModelIntrinsics(imu.kind, imu.model.Intrinsics());
    e.calibration.intrinsics.C_i_b = RotationFromBlock(imu.q_i_b.data()).matrix();
    e.calibration.intrinsics.r_b = imu.r_b;
    e.calibration.time_offset_s = imu.time_offset_s;
    e.lever_arm_held = imu.lever_arm_held;
    e.initial_time_offset_s = imu.initial_time_offset_s;
    e.initial_C_i_b = imu.initial_C_i_b;
    e.noise = imu.noise;
    e.rate_hz = imu.rate_hz;
    double gyro_sq = 0.0;
    double accel_sq = 0.0;
    for (const FurtherImuSegment& segment : Segments(imu)) {
      const std::vector<double*> blocks =
          Blocks(&imu, segment, spline.control_blocks(), g_w.data());
      const int nb = segment.bias_blocks;
      for (const FurtherImuSample& sample : segment.samples) {
        Eigen::Vector3d gyro;
        Eigen::Vector3d accel;
        PredictFurtherImu(segment, sample, blocks.data(), &gyro, &accel);
        gyro_sq += (gyro - sample.gyro).squaredNorm();
        accel_sq += (accel - sample.accel).squaredNorm();
        for (int j = 0; j < nb; ++j) {
          e.gyro_bias += sample.bias_weights[j] * Eigen::Map<const Eigen::Vector3d>(blocks[4 + j]);
          e.accel_bias +=
              sample.bias_weights[j] * Eigen::Map<const Eigen::Vector3d>(blocks[4 + nb + j]);
        }
        ++e.num_samples;
      }
    }
    const double n = std::max(1, e.num_samples);
    e.gyro_bias /= n;
    e.accel_bias /= n;
    e.gyro_rms = std::sqrt(gyro_sq / (3.0 * n));
    e.accel_rms = std::sqrt(accel_sq / (3.0 * n));
    out->push_back(e);
  }
}

void FurtherImus::StdFrom(const Eigen::MatrixXd& cov,
                          const std::map<const double*, int>& offset,
                          std::vector<FurtherImuEstimate>* out) const {
  for (size_t i = 0; i < imus_.size() && i < out->size(); ++i) {
    const State& imu = imus_[i];
    FurtherImuEstimate& e = (*out)[i];
    // AddCovarianceBlocks' order: C_i_b (its right tangent), r_b (no row when held), the time
    // offset, the model's blocks (a held entry has no row: ceres::SubsetManifold skips it).
    std::vector<CovarianceBlock> blocks = {
        {imu.q_i_b.data(), VectorCoordinates(ImuParameter::kCIB, 3), {}},
        {imu.r_b.data(), VectorCoordinates(ImuParameter::kRB, 3), {}},
        {&imu.time_offset_s, VectorCoordinates(ImuParameter::kTimeOffset, 1), {}}};
    const std::vector<CovarianceBlock> model =
        ModelCovarianceBlocks(imu.kind, imu.model, [&](const double* block) {
          const auto it = imu.held_model.find(block);
          return it == imu.held_model.end() ? std::vector<int>() : it->second;
        });
    blocks.insert(blocks.end(), model.begin(), model.end());
    e.covariance = CovarianceOfBlocks(cov, offset, blocks);
    e.model_std = ModelStdOf(e.covariance);
    auto diagonal = [&](ImuParameter parameter, int size) {
      Eigen::VectorXd d = Eigen::VectorXd::Constant(size, NaN());
      for (int k : e.covariance.Rows({parameter})) {
        d[e.covariance.entries[k].row] = std::sqrt(std::max(0.0, e.covariance.matrix(k, k)));
      }
      return d;
    };
    e.rotation_std_deg = diagonal(ImuParameter::kCIB, 3) * kRadToDeg;
    e.r_b_std_m = diagonal(ImuParameter::kRB, 3);
    e.time_offset_std_s = diagonal(ImuParameter::kTimeOffset, 1)(0);
  }
}

}  // namespace internal
}  // namespace splinecal
