#include "splinecal/estimation/imu_model_observability.h"

#include <ceres/ceres.h>

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

#include "splinecal/axis_name.h"

namespace splinecal {
namespace {

// Stds above which an estimate says nothing about the IMU: 1% of scale or misalignment (a
// consumer MEMS IMU's own errors, Rehder et al., ICRA 2016), 1e-2 (rad/s)/(m/s^2) of
// g-sensitivity (50x a MEMS gyro's typical 0.1 deg/s/g), 1 deg of gyro-frame rotation, 1 cm of
// an accelerometer axis' lever arm (the size of the IMU chip).
constexpr double kMatrixMeaningless = 0.01;
constexpr double kAMeaningless = 0.01;
constexpr double kRotationMeaninglessRad = 0.0175;
constexpr double kLeverArmMeaningless_m = 0.01;
// Eigenvalues below this fraction of the largest are raised to it (the file comment).
constexpr double kEigenFloor = 1e-12;

}  // namespace

std::vector<ImuModelParameter> ListImuModelParameters(ImuModelKind kind, ImuModelParameters* model) {
  std::vector<ImuModelParameter> list;
  if (kind == ImuModelKind::kCalibrated) return list;
  ImuModelParameters& m = *model;
  auto add = [&](double* block, int index, std::string name, std::string needs, double limit) {
    ImuModelParameter p;
    p.block = block;
    p.index = index;
    p.name = std::move(name);
    p.needs = std::move(needs);
    p.meaningless_std = limit;
    list.push_back(p);
  };
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c <= r; ++c) {
      const std::string rc = "(" + std::to_string(r) + "," + std::to_string(c) + ")";
      add(m.m_a.data(), LowerTriangularIndex(r, c), "M_a" + rc,
          std::string("specific force along the accelerometer's ") + AxisName(c) + " axis",
          kMatrixMeaningless);
      add(m.m_g.data(), LowerTriangularIndex(r, c), "M_g" + rc,
          std::string("rotation about the gyro's ") + AxisName(c) + " axis", kMatrixMeaningless);
    }
  }
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      add(m.a.data(), 3 * r + c, "A(" + std::to_string(r) + "," + std::to_string(c) + ")",
          std::string("specific force along the gyro's ") + AxisName(c) + " axis", kAMeaningless);
    }
  }
  for (int a = 0; a < 3; ++a) {
    add(m.phi_gyro_i.data(), a, std::string("C_gyro_i(") + AxisName(a) + ")",
        std::string("rotation about an axis other than ") + AxisName(a), kRotationMeaninglessRad);
  }
  if (kind == ImuModelKind::kScaleMisalignmentSizeEffect) {
    for (int a = 0; a < 3; ++a) {
      add(m.ry_i.data(), a, std::string("ry_i(") + AxisName(a) + ")",
          "angular velocity and acceleration about several axes", kLeverArmMeaningless_m);
      add(m.rz_i.data(), a, std::string("rz_i(") + AxisName(a) + ")",
          "angular velocity and acceleration about several axes", kLeverArmMeaningless_m);
    }
  }
  return list;
}

void SetLowerBoundStds(const Eigen::MatrixXd& information,
                       const std::vector<double*>& blocks,
                       const std::vector<int>& sizes,
                       std::vector<ImuModelParameter>* parameters) {
  std::vector<int> first(blocks.size());
  for (size_t b = 1; b < blocks.size(); ++b) first[b] = first[b - 1] + sizes[b - 1];
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(information);
  const double floor = std::max(kEigenFloor * eigen.eigenvalues().maxCoeff(),
                                std::numeric_limits<double>::min());
  const Eigen::VectorXd inverse = eigen.eigenvalues().cwiseMax(floor).cwiseInverse();
  for (ImuModelParameter& parameter : *parameters) {
    const size_t b = std::find(blocks.begin(), blocks.end(), parameter.block) - blocks.begin();
    const int column = first[b] + parameter.index;
    const Eigen::VectorXd v = eigen.eigenvectors().row(column).transpose();
    parameter.lower_bound_std = std::sqrt(v.cwiseAbs2().dot(inverse));
  }
}

std::vector<ImuModelParameter> ImuModelParameterStds(SplineProblem* problem) {
  std::vector<ImuModelParameter> list =
      ListImuModelParameters(problem->imu_model_kind(), problem->imu_model());
  if (list.empty()) return list;
  ceres::Problem& p = problem->problem();
  ceres::Problem::EvaluateOptions options;
  std::vector<double*> blocks = problem->ImuModelBlocks();
  options.parameter_blocks = blocks;
  std::vector<ceres::ResidualBlockId> ids;
  p.GetResidualBlocks(&ids);
  for (ceres::ResidualBlockId id : ids) {
    const ImuResidualKind kind = problem->ResidualKind(id);
    if (kind == ImuResidualKind::kGyro || kind == ImuResidualKind::kAccel) {
      options.residual_blocks.push_back(id);
    }
  }
  // The columns of each block's entries in the evaluated Jacobian.
  std::vector<int> sizes;
  int columns = 0;
  for (double* block : blocks) {
    sizes.push_back(p.ParameterBlockSize(block));
    columns += sizes.back();
  }
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(columns, columns);
  ceres::CRSMatrix J;
  if (!options.residual_blocks.empty() && p.Evaluate(options, nullptr, nullptr, nullptr, &J)) {
    for (int row = 0; row < J.num_rows; ++row) {
      for (int i = J.rows[row]; i < J.rows[row + 1]; ++i) {
        for (int k = J.rows[row]; k < J.rows[row + 1]; ++k) {
          information(J.cols[i], J.cols[k]) += J.values[i] * J.values[k];
        }
      }
    }
  }
  SetLowerBoundStds(information, blocks, sizes, &list);
  return list;
}

std::vector<ImuModelParameter> UndeterminedImuModelParameters(SplineProblem* problem) {
  std::vector<ImuModelParameter> undetermined;
  for (const ImuModelParameter& p : ImuModelParameterStds(problem)) {
    if (!(p.lower_bound_std <= p.meaningless_std)) undetermined.push_back(p);
  }
  return undetermined;
}

std::string UndeterminedImuModelWarning(const std::vector<ImuModelParameter>& undetermined) {
  if (undetermined.empty()) return "";
  std::map<std::string, std::string> by_motion;  // needs -> names
  for (const ImuModelParameter& p : undetermined) {
    std::string& names = by_motion[p.needs];
    names += (names.empty() ? "" : ", ") + p.name;
  }
  std::string text =
      "the IMU model's parameters that this recording does not determine are held at their "
      "nominal values (no std reported):";
  for (const auto& [needs, names] : by_motion) text += " " + names + " (needs " + needs + ");";
  text.back() = '.';
  return text;
}

}  // namespace splinecal
