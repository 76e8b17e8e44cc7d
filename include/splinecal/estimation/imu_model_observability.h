// Which parameters of an IMU model (estimation/detail/imu_model_costs.h) a recording determines.
//
// The model's parameters are only determined by motion that excites them (Yang et al., RSS 2020,
// list the degenerate motions): M_g's column c needs rotation about the gyro's axis c, M_a's and
// A's column c specific force along axis c, the rotation C_gyro_i about axis a rotation about
// the other two axes. A planar or constant-axis motion leaves some of them free, and an estimate
// reported with a std taken from a near-singular information would mean nothing.
//
// The test: the information J^T J of the model's parameters from the IMU residuals alone, with
// everything else (trajectory, biases, gravity) held at its current value. Its standard
// deviations are a LOWER bound of the full problem's (holding the rest removes correlations), so a
// parameter whose bound is already above its meaningless_std (below) is not determined by
// the recording. Near-zero eigenvalues (below 1e-12 of the largest) count as 1e-12 of it: the
// combinations they carry get the large std they deserve instead of a division by zero.
#ifndef SPLINECAL_ESTIMATION_IMU_MODEL_OBSERVABILITY_H_
#define SPLINECAL_ESTIMATION_IMU_MODEL_OBSERVABILITY_H_

#include <Eigen/Core>
#include <string>
#include <vector>

#include "splinecal/estimation/imu_model_parameters.h"
#include "splinecal/estimation/spline_problem.h"

namespace splinecal {

// One scalar parameter of the model: its block (SplineProblem::ImuModelBlocks) and index in it.
struct ImuModelParameter {
  double* block = nullptr;
  int index = 0;
  std::string name;            // "M_g(0,0)", "A(1,2)", "C_gyro_i(x)", "ry_i(z)"
  std::string needs;           // the motion that determines it, in words
  double meaningless_std = 0;  // a std above this says nothing (units of the parameter)
  double lower_bound_std = 0;  // the information's std with all else held (see above)
};

// Every parameter of a model of `kind` whose blocks are `model`'s (none for kCalibrated), its
// lower_bound_std unset: the reference IMU's (below) or a further IMU's (src/calib/further_imus.h).
std::vector<ImuModelParameter> ListImuModelParameters(ImuModelKind kind, ImuModelParameters* model);

// Sets each parameter's lower_bound_std from `information`, the information matrix of `blocks`
// (their entries' columns in that order, `sizes` entries each).
void SetLowerBoundStds(const Eigen::MatrixXd& information,
                       const std::vector<double*>& blocks,
                       const std::vector<int>& sizes,
                       std::vector<ImuModelParameter>* parameters);

// Every parameter of the problem's model (none for kCalibrated), with lower_bound_std from the
// problem's IMU residuals at its current values (call after AddImuResiduals).
std::vector<ImuModelParameter> ImuModelParameterStds(SplineProblem* problem);

// The parameters whose lower_bound_std exceeds meaningless_std.
std::vector<ImuModelParameter> UndeterminedImuModelParameters(SplineProblem* problem);

// The warning naming them, grouped by the motion each needs (empty for none).
std::string UndeterminedImuModelWarning(const std::vector<ImuModelParameter>& undetermined);

}  // namespace splinecal

#endif  // SPLINECAL_ESTIMATION_IMU_MODEL_OBSERVABILITY_H_
