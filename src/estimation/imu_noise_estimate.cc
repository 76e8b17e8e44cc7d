#include "splinecal/estimation/imu_noise_estimate.h"

#include <algorithm>
#include <array>
#include <cmath>

#include "splinecal/enum_names.h"

namespace splinecal {

namespace {

// The group of residuals SplineProblem did not add (reprojection, pose, a user's own).
constexpr int kOtherResiduals = kNumImuResidualKinds;

double* MutableDensity(ImuNoise* noise, int kind) {
  switch (static_cast<ImuResidualKind>(kind)) {
    case ImuResidualKind::kGyro:
      return &noise->gyroscope_noise_density;
    case ImuResidualKind::kAccel:
      return &noise->accelerometer_noise_density;
    case ImuResidualKind::kGyroRandomWalk:
      return &noise->gyroscope_random_walk;
    default:
      return &noise->accelerometer_random_walk;
  }
}

bool IsWhiteNoise(int kind) {
  return kind == static_cast<int>(ImuResidualKind::kGyro) ||
         kind == static_cast<int>(ImuResidualKind::kAccel);
}

}  // namespace

double ImuNoiseDensity(const ImuNoise& noise, ImuResidualKind kind) {
  ImuNoise copy = noise;
  return *MutableDensity(&copy, static_cast<int>(kind));
}

std::array<double, kNumImuResidualKinds> ImuNoiseEstimate::MeasuredOverGiven() const {
  std::array<double, kNumImuResidualKinds> ratios{};
  for (int k = 0; k < kNumImuResidualKinds; ++k) {
    const auto kind = static_cast<ImuResidualKind>(k);
    ratios[k] = ImuNoiseDensity(measured, kind) / ImuNoiseDensity(given, kind);
  }
  return ratios;
}

const char* ImuNoiseKey(ImuResidualKind kind) {
  static constexpr std::array<EnumName<ImuResidualKind>, kNumImuResidualKinds> kKeys = {{
      {ImuResidualKind::kGyro, "gyroscope_noise_density"},
      {ImuResidualKind::kAccel, "accelerometer_noise_density"},
      {ImuResidualKind::kGyroRandomWalk, "gyroscope_random_walk"},
      {ImuResidualKind::kAccelRandomWalk, "accelerometer_random_walk"},
  }};
  return kind == ImuResidualKind::kNotImu ? "" : NameOf(kKeys, kind);
}

ImuNoiseEstimator::ImuNoiseEstimator(const ImuNoise& given, double imu_rate_hz, ImuNoiseMode mode)
    : rate_hz_(imu_rate_hz) {
  estimate_.mode = mode;
  estimate_.given = given;
  estimate_.used = given;
  estimate_.measured = given;
}

int ImuNoiseEstimator::GroupOf(const SplineProblem& spline_problem, ceres::ResidualBlockId id) {
  const ImuResidualKind kind = spline_problem.ResidualKind(id);
  return kind == ImuResidualKind::kNotImu ? kOtherResiduals : static_cast<int>(kind);
}

std::map<int, double> ImuNoiseEstimator::NoiseFactors() const {
  std::map<int, double> factors;
  if (estimate_.mode == ImuNoiseMode::kGiven) return factors;
  for (int k : {static_cast<int>(ImuResidualKind::kGyro), static_cast<int>(ImuResidualKind::kAccel)}) {
    const auto kind = static_cast<ImuResidualKind>(k);
    const double ratio =
        ImuNoiseDensity(estimate_.measured, kind) / ImuNoiseDensity(estimate_.used, kind);
    factors[k] = ratio * ratio;
  }
  return factors;
}

bool ImuNoiseEstimator::AddToCovarianceOptions(const SplineProblem* spline_problem,
                                               double robust_window_s,
                                               MarginalCovarianceOptions* options) const {
  if (robust_window_s > 0.0) {
    options->cluster_of = [spline_problem, robust_window_s](ceres::ResidualBlockId id) {
      return spline_problem->TimeWindowOf(id, robust_window_s);
    };
  }
  options->noise_factors = NoiseFactors();
  if (!options->noise_factors.empty()) {
    options->group_of = [spline_problem](ceres::ResidualBlockId id) {
      return GroupOf(*spline_problem, id);
    };
  }
  return robust_window_s > 0.0 || !options->noise_factors.empty();
}

double ImuNoiseEstimator::Update(SplineProblem* spline_problem, int num_threads) {
  if (estimate_.mode == ImuNoiseMode::kGiven) return 0.0;
  // The random-walk prior's quadratic form has rank 3 (num_points - 1): a constant bias costs
  // nothing (estimation/bias_costs.h).
  const double prior_rank = 3.0 * (spline_problem->bias_spline().num_points() - 1);
  VarianceComponentOptions options;
  options.num_threads = num_threads;
  const VarianceComponents components = EstimateVarianceComponents(
      &spline_problem->problem(),
      [spline_problem](ceres::ResidualBlockId id) { return GroupOf(*spline_problem, id); },
      options,
      {{static_cast<int>(ImuResidualKind::kGyroRandomWalk), prior_rank},
       {static_cast<int>(ImuResidualKind::kAccelRandomWalk), prior_rank}});
  if (!components.ok) return 0.0;
  ++estimate_.updates;
  double change = 0.0;
  for (int k = 0; k < kNumImuResidualKinds; ++k) {
    const auto it = components.groups.find(k);
    if (it == components.groups.end()) continue;  // no such residuals (a constant bias)
    const VarianceComponent& group = it->second;
    estimate_.num_residuals[k] = group.num_residuals;
    estimate_.redundancy[k] = group.redundancy;
    estimate_.determined[k] = group.identifiable;
    if (!group.identifiable || !(group.factor > 0.0) || !std::isfinite(group.factor)) continue;
    // f_l is relative to the weights of this solve.
    const double scale = std::sqrt(group.factor);
    *MutableDensity(&estimate_.measured, k) = *MutableDensity(&estimate_.used, k) * scale;
    const bool reweight = !IsWhiteNoise(k) || estimate_.mode == ImuNoiseMode::kReweighted;
    if (!reweight) continue;
    *MutableDensity(&estimate_.used, k) *= scale;
    change = std::max(change, std::abs(scale - 1.0));
  }
  return change;
}

}  // namespace splinecal
