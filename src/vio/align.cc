#include "splinecal/vio/align.h"

#include <glog/logging.h>

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "splinecal/estimation/gravity_tangent.h"
#include "splinecal/vio/hand_eye.h"
#include "splinecal/error.h"
#include "splinecal/string_printf.h"
#include "align_checks.h"

namespace splinecal {
namespace {

constexpr double kInfinity = std::numeric_limits<double>::infinity();

// An iteration whose step is below this [rad, rad/s] but no smaller than half the previous step
// has reached the rounding floor: more iterations only shuffle the last digits.
constexpr double kStallStep = 1e-9;
constexpr double kStallRatio = 0.5;

// Gyro-bias iterations re-integrate the rotations only when the bias moved more than this
// [rad/s] from where they were integrated (see EstimateGyroBias).
constexpr double kRelinearizeBias = 1e-6;

using NormalEquations = AlignmentProblem::NormalEquations;

bool Converged(double step, double previous_step, double tolerance) {
  return step < tolerance || (step < kStallStep && step > kStallRatio * previous_step);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// AlignmentProblem

AlignmentProblem::AlignmentProblem(const std::vector<ImuSample>& imu,
                                   std::vector<AlignmentFrame> frames,
                                   const SE3d& T_cam_imu,
                                   const Eigen::Vector3d& gyro_bias,
                                   const Eigen::Vector3d& accel_bias,
                                   const ImuNoise& noise,
                                   const CameraNoise& camera_noise)
    : frames_(std::move(frames)),
      T_cam_imu_(T_cam_imu),
      camera_position_variance_(camera_noise.position_std_m * camera_noise.position_std_m),
      accel_walk_variance_(noise.accelerometer_random_walk * noise.accelerometer_random_walk) {
  if (frames_.size() < 3) {
    throw Error("alignment needs at least 3 camera frames, got " + std::to_string(frames_.size()));
  }
  preintegrations_.reserve(frames_.size() - 1);
  information_.reserve(frames_.size() - 1);
  for (size_t k = 0; k + 1 < frames_.size(); ++k) {
    preintegrations_.push_back(
        Preintegrate(imu, frames_[k].t_ns, frames_[k + 1].t_ns, gyro_bias, accel_bias, &noise));
    // Weight = inverse covariance of (dp, dv) (vio/preintegration.h).
    const ImuPreintegration& pre = preintegrations_.back();
    Eigen::Matrix<double, 6, 6> covariance = pre.covariance.topLeftCorner<6, 6>();
    // Camera noise: positions n_k (metric) enter r_p as R^T (n_k+1 - n_k); a rotation error
    // R_c0_sk Exp(e) turns R^T x into R^T x + [R^T x]x e with R^T x = dp (p rows), dv (v rows).
    const double var_p = camera_position_variance_;
    const double var_r = camera_noise.rotation_std_rad * camera_noise.rotation_std_rad;
    Eigen::Matrix<double, 6, 3> E;
    E << Hat(pre.delta_p), Hat(pre.delta_v);
    covariance += var_r * E * E.transpose();
    covariance.topLeftCorner<3, 3>().diagonal().array() += 2.0 * var_p;
    const Eigen::LLT<Eigen::Matrix<double, 6, 6>> llt(covariance);
    if (llt.info() != Eigen::Success) {
      throw Error(
          "alignment: the preintegration covariance is not positive definite (are the "
          "IMU noise densities positive?)");
    }
    information_.push_back(llt.solve(Eigen::Matrix<double, 6, 6>::Identity()));
  }
}

NormalEquations AlignmentProblem::Build(
    const Eigen::Vector3d& gravity_per_u,
    const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3>& gravity_basis,
    bool with_accel_bias) const {
  const int n = num_frames();
  const int m_g = static_cast<int>(gravity_basis.cols());
  const int m_b = with_accel_bias ? 3 : 0;
  const int m = m_g + m_b + 1;  // gravity coordinates, accel bias b'_a, then u = 1 / s
  const int col_u = 6 + m - 1;
  NormalEquations eq;
  eq.m = m;
  eq.num_rows = 6 * (n - 1);
  eq.D.assign(n, Eigen::Matrix3d::Zero());
  eq.C.assign(n - 1, Eigen::Matrix3d::Zero());
  eq.H_vy.assign(n, NormalEquations::Matrix3Y::Zero(3, m));
  eq.H_yy = NormalEquations::MatrixY::Zero(m, m);
  eq.b_v.assign(n, Eigen::Vector3d::Zero());
  eq.b_y = NormalEquations::VectorY::Zero(m);
  eq.pairs.resize(n - 1);
  eq.camera_position_variance = camera_position_variance_;
  eq.accel_walk_variance = accel_walk_variance_;

  const SO3d& R_c_s = T_cam_imu_.so3();
  const Eigen::Vector3d& t_c_s = T_cam_imu_.translation();
  constexpr int kMaxCols = 6 + NormalEquations::kMaxM;
  using Jacobian = Eigen::Matrix<double, 6, Eigen::Dynamic, 0, 6, kMaxCols>;
  for (int k = 0; k + 1 < n; ++k) {
    const AlignmentFrame& f0 = frames_[k];
    const AlignmentFrame& f1 = frames_[k + 1];
    const ImuPreintegration& pre = preintegrations_[k];
    const double T = pre.dt_s;
    // R_c0_sk^T, and the lever arms l = R_c0_c t_c_s of equation (1) in align.h.
    const Eigen::Matrix3d Rt = (f0.R_c0_c * R_c_s).matrix().transpose();
    const Eigen::Vector3d delta_lever = f1.R_c0_c * t_c_s - f0.R_c0_c * t_c_s;
    const Eigen::Vector3d delta_p_bar = f1.p_c0_c - f0.p_c0_c;

    // Residual r = J x - b in camera units, x = (v'_k, v'_k+1, y_g, u) (align.h, step 3), with
    // g' = gravity_per_u u + gravity_basis y_g:
    //   r_p = Rt (v'_k T + g' T^2/2 - u dl) + u dp - Rt dp_bar [+ J_dp_ba b'_a]
    //   r_v = Rt (v'_k+1 - v'_k - g' T) - u dv                   [- J_dv_ba b'_a]
    // (u dp(b_a + db) ~ u dp + J_dp_ba u db, preintegration.h; b'_a = u db is linear.)
    const Eigen::Vector3d g_u_rot = Rt * gravity_per_u;
    const Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, 3> basis_rot = Rt * gravity_basis;
    Jacobian J = Jacobian::Zero(6, 6 + m);
    J.block<3, 3>(0, 0) = T * Rt;
    J.block(0, 6, 3, m_g) = (0.5 * T * T) * basis_rot;
    J.block<3, 1>(0, col_u) = 0.5 * T * T * g_u_rot - Rt * delta_lever + pre.delta_p;
    J.block<3, 3>(3, 0) = -Rt;
    J.block<3, 3>(3, 3) = Rt;
    J.block(3, 6, 3, m_g) = -T * basis_rot;
    J.block<3, 1>(3, col_u) = -T * g_u_rot - pre.delta_v;
    if (with_accel_bias) {
      J.block<3, 3>(0, 6 + m_g) = pre.J_dp_ba;
      J.block<3, 3>(3, 6 + m_g) = -pre.J_dv_ba;
    }
    Eigen::Matrix<double, 6, 1> b;
    b.head<3>() = Rt * delta_p_bar;
    b.tail<3>().setZero();

    const Eigen::Matrix<double, Eigen::Dynamic, 6, 0, kMaxCols, 6> JtW =
        J.transpose() * information_[k];
    const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, kMaxCols, kMaxCols> H = JtW * J;
    const Eigen::Matrix<double, Eigen::Dynamic, 1, 0, kMaxCols, 1> g = JtW * b;
    eq.rhs_weighted_sq += b.dot(information_[k] * b);
    NormalEquations::Pair& pair = eq.pairs[k];
    pair.JtW = JtW;
    pair.Rt = Rt;
    pair.d_rows_d_accel_bias << pre.J_dp_ba, -pre.J_dv_ba;
    pair.duration_s = T;
    eq.D[k] += H.block<3, 3>(0, 0);
    eq.D[k + 1] += H.block<3, 3>(3, 3);
    eq.C[k] += H.block<3, 3>(0, 3);
    eq.H_vy[k] += H.block(0, 6, 3, m);
    eq.H_vy[k + 1] += H.block(3, 6, 3, m);
    eq.H_yy += H.block(6, 6, m, m);
    eq.b_v[k] += g.segment<3>(0);
    eq.b_v[k + 1] += g.segment<3>(3);
    eq.b_y += g.segment(6, m);
  }
  return eq;
}

namespace {

// The part of Cov(y) that the pairs' weights leave out, at unit variance factor (docs/align.md,
// "Uncertainty"). y = A r for the weighted least-squares solution, with A's block for pair k
// G_k = S^-1 (JtW_k,y - Y_k^T JtW_k,v_k - Y_k+1^T JtW_k,v_k+1) (the rows of H^-1 for y are
// S^-1 [-Y^T, I], Y = H_vv^-1 H_vy). S^-1 = A W^-1 A^T counts each pair's noise alone; added:
//  * a camera position n_j (frame j, variance sigma_p^2 per axis) enters pair j-1 as +R^T n_j and
//    pair j as -R^T n_j: the cross terms -sigma_p^2 (X_a X_b^T + X_b X_a^T), X = G^p R^T;
//  * the accelerometer bias walk: the increment during pair i (variance density^2 T_i per axis)
//    offsets the bias of every later pair k > i, whose rows move by B_k = [J_dp_ba; -J_dv_ba]:
//    density^2 T_i F_i F_i^T with F_i = sum_{k>i} G_k B_k. (The walk inside a pair is in its
//    preintegration covariance; the gyro bias walk is left out: 2e-6 of the scale against 7e-4
//    for the accelerometer's, docs/align.md.)
NormalEquations::MatrixY SharedNoiseCovariance(const NormalEquations& eq,
                                               const std::vector<NormalEquations::Matrix3Y>& Y,
                                               const NormalEquations::MatrixY& S_inverse) {
  const int m = eq.m;
  const int num_pairs = static_cast<int>(eq.pairs.size());
  CHECK_EQ(num_pairs + 1, static_cast<int>(Y.size()))
      << "the shared-noise covariance needs the rows of one Build (not after AccumulateScaled)";
  using MatrixY6 = Eigen::Matrix<double, Eigen::Dynamic, 6, 0, NormalEquations::kMaxM, 6>;
  using MatrixY3 = Eigen::Matrix<double, Eigen::Dynamic, 3, 0, NormalEquations::kMaxM, 3>;
  std::vector<MatrixY6> G(num_pairs);
  for (int k = 0; k < num_pairs; ++k) {
    const auto& JtW = eq.pairs[k].JtW;
    G[k] = S_inverse * (JtW.bottomRows(m) - Y[k].transpose() * JtW.topRows<3>() -
                        Y[k + 1].transpose() * JtW.middleRows<3>(3));
  }
  NormalEquations::MatrixY extra = NormalEquations::MatrixY::Zero(m, m);
  for (int j = 1; j < num_pairs; ++j) {
    const MatrixY3 X_a = G[j - 1].leftCols<3>() * eq.pairs[j - 1].Rt;
    const MatrixY3 X_b = G[j].leftCols<3>() * eq.pairs[j].Rt;
    extra.noalias() -= eq.camera_position_variance * (X_a * X_b.transpose());
    extra.noalias() -= eq.camera_position_variance * (X_b * X_a.transpose());
  }
  MatrixY3 F = MatrixY3::Zero(m, 3);
  for (int i = num_pairs - 2; i >= 0; --i) {
    F.noalias() += G[i + 1] * eq.pairs[i + 1].d_rows_d_accel_bias;
    extra.noalias() += (eq.accel_walk_variance * eq.pairs[i].duration_s) * (F * F.transpose());
  }
  return extra;
}

}  // namespace

void NormalEquations::AccumulateScaled(const NormalEquations& other, double factor) {
  CHECK_EQ(m, other.m);
  CHECK_EQ(D.size(), other.D.size());
  for (size_t k = 0; k < D.size(); ++k) {
    D[k] = factor * (D[k] + other.D[k]);
    H_vy[k] = factor * (H_vy[k] + other.H_vy[k]);
    b_v[k] = factor * (b_v[k] + other.b_v[k]);
  }
  for (size_t k = 0; k < C.size(); ++k) C[k] = factor * (C[k] + other.C[k]);
  H_yy = factor * (H_yy + other.H_yy);
  b_y = factor * (b_y + other.b_y);
  rhs_weighted_sq = factor * (rhs_weighted_sq + other.rhs_weighted_sq);
  num_rows += other.num_rows;
  // The accumulated system has no single set of rows: Solve's shared_noise_covariance does not
  // apply to it.
  pairs.clear();
}

double NormalEquations::Solve(std::vector<Eigen::Vector3d>* v,
                              VectorY* y,
                              MatrixY* inverse_schur,
                              double* chi2,
                              MatrixY* shared_noise_covariance) const {
  const int n = static_cast<int>(D.size());
  using Matrix3Yb = Eigen::Matrix<double, 3, Eigen::Dynamic, 0, 3, kMaxM + 1>;  // [H_vy | b_v]
  // Block Thomas algorithm on H_vv (block tridiagonal, symmetric positive definite):
  //   P_0 = D_0,  P_k = D_k - C_k-1^T P_k-1^-1 C_k-1,   Z_k = X_k - C_k-1^T P_k-1^-1 Z_k-1
  // then Y_n-1 = P_n-1^-1 Z_n-1, Y_k = P_k^-1 (Z_k - C_k Y_k+1), so Y = H_vv^-1 [H_vy | b_v].
  std::vector<Eigen::LLT<Eigen::Matrix3d>> P(n);
  std::vector<Matrix3Yb> Z(n);
  for (int k = 0; k < n; ++k) {
    Matrix3Yb X(3, m + 1);
    X << H_vy[k], b_v[k];
    if (k == 0) {
      P[k].compute(D[k]);
      Z[k] = X;
    } else {
      const Eigen::Matrix3d Lt = P[k - 1].solve(C[k - 1]);  // P_k-1^-1 C_k-1
      P[k].compute(D[k] - Lt.transpose() * C[k - 1]);
      Z[k] = X - Lt.transpose() * Z[k - 1];
    }
    if (P[k].info() != Eigen::Success) return kInfinity;
  }
  std::vector<Matrix3Yb> Y(n);
  Y[n - 1] = P[n - 1].solve(Z[n - 1]);
  for (int k = n - 2; k >= 0; --k) Y[k] = P[k].solve(Z[k] - C[k] * Y[k + 1]);

  // Schur complement in y: S = H_yy - H_vy^T H_vv^-1 H_vy, t = b_y - H_vy^T H_vv^-1 b_v.
  MatrixY S = H_yy;
  VectorY t = b_y;
  for (int k = 0; k < n; ++k) {
    S.noalias() -= H_vy[k].transpose() * Y[k].leftCols(m);
    t.noalias() -= H_vy[k].transpose() * Y[k].col(m);
  }
  // Scale to the diagonal of H_yy: S_hat = D^-1/2 S D^-1/2. Its eigenvalues lie in [0, m]; the
  // smallest is the fraction of the information on the worst-determined combination of
  // (gravity, scale) that the velocities and the other unknowns do not absorb.
  const VectorY d = H_yy.diagonal();
  if ((d.array() <= 0.0).any() || !d.allFinite()) return kInfinity;
  const VectorY scaling = d.cwiseSqrt().cwiseInverse();
  const MatrixY S_hat = scaling.asDiagonal() * S * scaling.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<MatrixY> eigen(S_hat);
  const double lambda_min = eigen.eigenvalues()(0);
  const double lambda_max = eigen.eigenvalues()(m - 1);
  if (!(lambda_min > 0.0)) return kInfinity;
  const VectorY y_hat =
      eigen.eigenvectors() * (eigen.eigenvalues().cwiseInverse().asDiagonal() *
                              (eigen.eigenvectors().transpose() * scaling.asDiagonal() * t));
  *y = scaling.asDiagonal() * y_hat;
  v->resize(n);
  for (int k = 0; k < n; ++k) (*v)[k] = Y[k].col(m) - Y[k].leftCols(m) * (*y);
  // S^-1 = D^-1/2 S_hat^-1 D^-1/2, from the eigen-decomposition already at hand.
  const MatrixY S_inverse =
      scaling.asDiagonal() *
      (eigen.eigenvectors() * eigen.eigenvalues().cwiseInverse().asDiagonal() *
       eigen.eigenvectors().transpose()) *
      scaling.asDiagonal();
  if (inverse_schur != nullptr) *inverse_schur = S_inverse;
  if (shared_noise_covariance != nullptr) {
    std::vector<Matrix3Y> coupling(n);  // H_vv^-1 H_vy
    for (int k = 0; k < n; ++k) coupling[k] = Y[k].leftCols(m);
    *shared_noise_covariance = S_inverse + SharedNoiseCovariance(*this, coupling, S_inverse);
  }
  if (chi2 != nullptr) {
    // r^T W r = b^T W b - 2 x^T g + x^T H x = b^T W b - x^T g at H x = g. Cancellation leaves
    // rounding-sized negatives on noise-free data: clamp.
    double x_dot_g = y->dot(b_y);
    for (int k = 0; k < n; ++k) x_dot_g += (*v)[k].dot(b_v[k]);
    *chi2 = std::max(0.0, rhs_weighted_sq - x_dot_g);
  }
  return std::sqrt(lambda_max / lambda_min);
}

namespace {

// Solves eq and fills the scale, the velocities and the uncertainty of equation (2) in align.h.
// Returns y (u last), the covariance of y with the residual-estimated noise in *covariance_y;
// an empty y when the system is singular.
NormalEquations::VectorY SolveWithUncertainty(const NormalEquations& eq,
                                              AlignmentSolution* solution,
                                              NormalEquations::MatrixY* covariance_y) {
  std::vector<Eigen::Vector3d> v_prime;
  NormalEquations::VectorY y;
  NormalEquations::MatrixY unit_covariance;
  double chi2 = 0.0;
  solution->condition_number = eq.Solve(&v_prime, &y, nullptr, &chi2, &unit_covariance);
  const int m = eq.m;
  if (!std::isfinite(solution->condition_number) || !(y(m - 1) != 0.0)) {
    solution->condition_number = kInfinity;
    return NormalEquations::VectorY();
  }
  // x' = x / s: s = 1 / u, v = v' / u.
  const double u = y(m - 1);
  solution->scale = 1.0 / u;
  for (size_t k = 0; k < v_prime.size(); ++k) solution->v_c0[k] = v_prime[k] / u;
  // Equation (2): the residuals are in camera units, r = r_metric / s, weighted with the metric
  // information W: chi2 = chi2_metric / s^2. The variance factor chi2 / dof then scales the
  // unit covariance (S^-1 plus the noise shared between pairs) to the covariance of y, and
  // sqrt(chi2_metric / dof) compares the residuals with the assumed noise. s = 1/u:
  // sigma_s = sigma_u / u^2 (first order).
  const int dof = eq.num_rows - eq.num_unknowns();
  if (dof <= 0) {
    solution->scale_std = kInfinity;
    solution->residual_noise_ratio = kInfinity;
    *covariance_y = NormalEquations::MatrixY::Constant(m, m, kInfinity);
    return y;
  }
  const double variance_factor = chi2 / dof;
  *covariance_y = variance_factor * unit_covariance;
  solution->scale_std = std::sqrt(std::max(0.0, (*covariance_y)(m - 1, m - 1))) / (u * u);
  solution->residual_noise_ratio = std::sqrt(variance_factor) * std::abs(solution->scale);
  return y;
}

}  // namespace

AlignmentSolution AlignmentProblem::SolveFreeGravity() const {
  AlignmentSolution solution;
  solution.iterations = 1;
  solution.v_c0.assign(frames_.size(), Eigen::Vector3d::Zero());
  NormalEquations::MatrixY covariance_y;
  const NormalEquations::VectorY y = SolveWithUncertainty(
      Build(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity()), &solution, &covariance_y);
  if (y.size() == 0) return solution;
  solution.gravity_c0 = y.head<3>() / y(3);  // g = g' / u
  solution.converged = true;
  return solution;
}

AlignmentSolution AlignmentProblem::SolveFreeGravityWithAccelBias() const {
  AlignmentSolution solution;
  solution.iterations = 1;
  solution.v_c0.assign(frames_.size(), Eigen::Vector3d::Zero());
  NormalEquations::MatrixY covariance_y;
  const NormalEquations::VectorY y =
      SolveWithUncertainty(Build(Eigen::Vector3d::Zero(), Eigen::Matrix3d::Identity(), true),
                           &solution,
                           &covariance_y);
  if (y.size() == 0) return solution;
  // y = (g', b'_a, u): g = g' / u, db_a = b'_a / u; its covariance to first order through
  // d(b'/u) = db' / u - b' du / u^2.
  const double u = y(6);
  solution.gravity_c0 = y.head<3>() / u;
  const Eigen::Vector3d b_prime = y.segment<3>(3);
  solution.accel_bias = preintegrations_.front().accel_bias + b_prime / u;
  Eigen::Matrix<double, 3, 4> J_b;
  J_b << Eigen::Matrix3d::Identity() / u, -b_prime / (u * u);
  const Eigen::Matrix4d covariance_bu = covariance_y.bottomRightCorner(4, 4);
  solution.accel_bias_std =
      (J_b * covariance_bu * J_b.transpose()).diagonal().cwiseMax(0.0).cwiseSqrt();
  solution.converged = true;
  return solution;
}

AlignmentSolution AlignmentProblem::RefineGravity(const AlignmentSolution& initial,
                                                  double gravity_norm,
                                                  double tolerance_rad,
                                                  int max_iterations) const {
  CHECK_GT(gravity_norm, 0.0);
  AlignmentSolution solution;
  solution.v_c0.assign(frames_.size(), Eigen::Vector3d::Zero());
  Eigen::Vector3d direction = initial.gravity_c0.normalized();
  double u0 = 1.0 / initial.scale;
  double previous_step = kInfinity;
  for (int iteration = 1; iteration <= max_iterations; ++iteration) {
    // Rebuild the rows at the current (d, u0) [seed001]: g' = u G Retract(d, w)
    //   ~ G d u + G u0 B(d) w   (w in radians; first order in w and in u - u0).
    // The last iteration's uncertainty is the solution's (its step is below the tolerance).
    const Eigen::Matrix<double, 3, 2> basis = GravityTangentBasis(direction);
    NormalEquations::MatrixY covariance_y;
    const NormalEquations::VectorY y = SolveWithUncertainty(
        Build(gravity_norm * direction, (gravity_norm * u0) * basis), &solution, &covariance_y);
    solution.iterations = iteration;
    if (y.size() == 0) break;
    const double u = y(2);
    // The tangent step the solve found is G u0 B w, the model's is G u B w: rescale.
    const Eigen::Vector2d w = y.head<2>() * (u0 / u);
    direction = RetractGravity(direction, w);
    u0 = u;
    const double step = w.norm();
    if (Converged(step, previous_step, tolerance_rad)) {
      solution.converged = true;
      break;
    }
    previous_step = step;
  }
  solution.gravity_c0 = gravity_norm * direction;
  return solution;
}

namespace internal {

AlignmentSolution RefineGravityAccumulating(const AlignmentProblem& problem,
                                            const AlignmentSolution& initial,
                                            double gravity_norm,
                                            int iterations) {
  // VINS-Mono's RefineGravity: A and b are zeroed once, before the loop; every iteration adds
  // the rows linearised at its g0, multiplies A and b by 1000, solves, and moves g0 by the
  // tangent step (normalised back to the sphere). Same formulation as RefineGravity otherwise.
  constexpr double kVinsFactor = 1000.0;
  AlignmentSolution solution;
  solution.v_c0.assign(problem.num_frames(), Eigen::Vector3d::Zero());
  Eigen::Vector3d direction = initial.gravity_c0.normalized();
  double u0 = 1.0 / initial.scale;
  NormalEquations total;
  std::vector<Eigen::Vector3d> v_prime;
  for (int iteration = 1; iteration <= iterations; ++iteration) {
    const Eigen::Matrix<double, 3, 2> basis = GravityTangentBasis(direction);
    const NormalEquations eq = problem.Build(gravity_norm * direction, (gravity_norm * u0) * basis);
    if (iteration == 1) {
      total = eq;
      total.AccumulateScaled(eq, 0.0);  // zero, with the right sizes
    }
    total.AccumulateScaled(eq, kVinsFactor);
    NormalEquations::VectorY y;
    solution.condition_number = total.Solve(&v_prime, &y);
    solution.iterations = iteration;
    if (!std::isfinite(solution.condition_number) || !(y(2) != 0.0)) break;
    const double u = y(2);
    direction = (direction + basis * (y.head<2>() * (u0 / u))).normalized();
    u0 = u;
    solution.scale = 1.0 / u;
    for (size_t k = 0; k < v_prime.size(); ++k) solution.v_c0[k] = v_prime[k] / u;
  }
  solution.gravity_c0 = gravity_norm * direction;
  solution.converged = true;
  return solution;
}

}  // namespace internal

// ---------------------------------------------------------------------------------------------
// Gyro bias (and camera-IMU rotation)

GyroBiasEstimate EstimateGyroBias(const std::vector<ImuSample>& imu,
                                  const std::vector<AlignmentFrame>& frames,
                                  const SO3d& R_cam_imu_initial,
                                  bool estimate_rotation,
                                  const AlignOptions& options) {
  CHECK_GE(frames.size(), 2u);
  GyroBiasEstimate estimate;
  estimate.gyro_bias = options.initial_gyro_bias;
  estimate.R_cam_imu = R_cam_imu_initial;
  const int num_pairs = static_cast<int>(frames.size()) - 1;
  std::vector<SO3d> R_ck_ck1(num_pairs);
  for (int k = 0; k < num_pairs; ++k) {
    R_ck_ck1[k] = frames[k].R_c0_c.inverse() * frames[k + 1].R_c0_c;
  }
  const int num_params = estimate_rotation ? 6 : 3;  // (db_g, dphi)
  double previous_step = kInfinity;
  // Rotations preintegrated at b_lin; for a bias within kRelinearizeBias of b_lin the first-order
  // correction dR(b) = dR(b_lin) Exp(J (b - b_lin)) is used instead (error O(|b - b_lin|^2 T^2)
  // < 1e-14 rad), which saves the last re-integrations.
  std::vector<SO3d> dR_lin(num_pairs);
  std::vector<Eigen::Matrix3d> J_lin(num_pairs);
  Eigen::Vector3d b_lin = Eigen::Vector3d::Zero();
  bool linearised = false;
  for (int iteration = 1; iteration <= options.max_gyro_bias_iterations; ++iteration) {
    // Gauss-Newton on r_k = Log(dR_k(b_g)^T X^T Rc_k X), X = R_cam_imu (align.h, step 2):
    //   dR(b + db)^T = Exp(-J_dR_bg db) dR^T              => dr/d db   = -Jl^-1(r) J_dR_bg
    //   X Exp(dphi): M = X^T Rc X -> Exp(-dphi) M Exp(dphi) ~ Exp((M - I) dphi) M
    //                                                     => dr/d dphi = Jl^-1(r) dR^T (M - I)
    // using Log(Exp(e) E) ~ Log(E) + Jl^-1(Log(E)) e [Sola18]. Pairs weighted by 1 / T_k, the
    // inverse of the white-gyro variance of their rotation.
    Eigen::Matrix<double, 6, 6> H = Eigen::Matrix<double, 6, 6>::Zero();
    Eigen::Matrix<double, 6, 1> gradient = Eigen::Matrix<double, 6, 1>::Zero();
    double sum_sq = 0.0;
    if (!linearised || (estimate.gyro_bias - b_lin).norm() > kRelinearizeBias) {
      for (int k = 0; k < num_pairs; ++k) {
        dR_lin[k] = PreintegrateRotation(
            imu, frames[k].t_ns, frames[k + 1].t_ns, estimate.gyro_bias, &J_lin[k]);
      }
      b_lin = estimate.gyro_bias;
      linearised = true;
    }
    for (int k = 0; k < num_pairs; ++k) {
      const Eigen::Matrix3d& J_dR_bg = J_lin[k];
      const SO3d dR = dR_lin[k] * SO3d::Exp(J_dR_bg * (estimate.gyro_bias - b_lin));
      const double weight =
          1e9 / static_cast<double>(frames[k + 1].t_ns - frames[k].t_ns);  // 1 / T_k [1/s]
      const SO3d M = estimate.R_cam_imu.inverse() * R_ck_ck1[k] * estimate.R_cam_imu;
      const Eigen::Vector3d r = (dR.inverse() * M).Log();
      const Eigen::Matrix3d Jl_inv = LeftJacobianInverseSO3(r);
      Eigen::Matrix<double, 3, 6> J;
      J.leftCols<3>() = -Jl_inv * J_dR_bg;
      J.rightCols<3>() =
          Jl_inv * dR.matrix().transpose() * (M.matrix() - Eigen::Matrix3d::Identity());
      H.noalias() += weight * J.transpose() * J;
      gradient.noalias() += weight * J.transpose() * r;
      sum_sq += r.squaredNorm();
    }
    estimate.rms_rotation_residual_rad = std::sqrt(sum_sq / num_pairs);
    estimate.iterations = iteration;
    Eigen::Matrix<double, 6, 1> delta = Eigen::Matrix<double, 6, 1>::Zero();
    delta.head(num_params) =
        -H.topLeftCorner(num_params, num_params).ldlt().solve(gradient.head(num_params));
    if (!delta.allFinite()) break;
    estimate.gyro_bias += delta.head<3>();
    if (estimate_rotation) estimate.R_cam_imu = estimate.R_cam_imu * SO3d::Exp(delta.tail<3>());
    const double step = delta.norm();
    if (Converged(step, previous_step, options.gyro_bias_tolerance_rad_s)) {
      estimate.converged = true;
      break;
    }
    previous_step = step;
  }
  return estimate;
}

SO3d GravityAlignedRotation(const Eigen::Vector3d& gravity_c0) {
  // Smallest rotation taking the direction of g_c0 to -z, then a rotation about z that sets the
  // ZYX yaw atan2(R(1,0), R(0,0)) to zero (it keeps -z fixed).
  const Eigen::Quaterniond q_min =
      Eigen::Quaterniond::FromTwoVectors(gravity_c0.normalized(), -Eigen::Vector3d::UnitZ());
  const Eigen::Matrix3d R_min = q_min.toRotationMatrix();
  const double yaw = std::atan2(R_min(1, 0), R_min(0, 0));
  const Eigen::Quaterniond q_yaw(Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()));
  return SO3d::FromQuaternion(q_yaw * q_min);
}

// ---------------------------------------------------------------------------------------------
// The whole alignment


AlignResult Align(const std::vector<ImuSample>& imu,
                  const std::vector<StampedPose>& camera_poses,
                  const AlignOptions& options) {
  const double G = options.gravity_m_s2;
  if (!std::isfinite(G) || G <= 0.0) throw Error("alignment: gravity must be a positive number");
  const ImuNoise& noise = options.noise;
  for (double density : {noise.gyroscope_noise_density,
                         noise.accelerometer_noise_density,
                         noise.gyroscope_random_walk,
                         noise.accelerometer_random_walk}) {
    if (!std::isfinite(density) || density <= 0.0) {
      throw Error("alignment: the IMU noise densities must be positive numbers");
    }
  }
  if (imu.size() < 2) throw Error("alignment: need at least 2 IMU samples");

  AlignResult result;
  // Camera poses in IMU time, inside the IMU data, relative to the first one used.
  const int64_t shift_ns = std::llround(options.time_offset_s * 1e9);
  std::vector<AlignmentFrame> frames;
  SE3d T_first_c0;  // T_c0_input: the inverse of the first used pose
  for (const StampedPose& pose : camera_poses) {
    const int64_t t_ns = pose.t_ns + shift_ns;
    if (t_ns < imu.front().t_ns || t_ns > imu.back().t_ns) {
      ++result.num_ignored_frames;
      continue;
    }
    const SE3d T_in_c(SO3d::FromQuaternion(pose.q), pose.p);
    if (frames.empty()) T_first_c0 = T_in_c.inverse();
    const SE3d T_c0_c = T_first_c0 * T_in_c;
    AlignmentFrame frame;
    frame.t_ns = t_ns;
    frame.R_c0_c = T_c0_c.so3();
    frame.p_c0_c = T_c0_c.translation();
    frames.push_back(frame);
  }
  if (frames.size() < 3) {
    throw Error(
        StringPrintf("alignment: need at least 3 camera poses inside the IMU data's time span "
                     "[%.9f, %.9f] s, found %d",
                     imu.front().t_ns * 1e-9,
                     imu.back().t_ns * 1e-9,
                     static_cast<int>(frames.size())));
  }

  // Step 1: camera-IMU rotation by hand-eye.
  SO3d R_cam_imu = options.T_cam_imu.so3();
  result.rotation_extrinsic_estimated = options.estimate_rotation_extrinsic;
  if (options.estimate_rotation_extrinsic) {
    std::vector<SO3d> R_ck_ck1, R_sk_sk1;
    for (size_t k = 0; k + 1 < frames.size(); ++k) {
      R_ck_ck1.push_back(frames[k].R_c0_c.inverse() * frames[k + 1].R_c0_c);
      R_sk_sk1.push_back(PreintegrateRotation(
          imu, frames[k].t_ns, frames[k + 1].t_ns, options.initial_gyro_bias, nullptr));
    }
    HandEyeOptions hand_eye_options;
    hand_eye_options.min_second_axis_ratio = options.min_hand_eye_second_axis_ratio;
    hand_eye_options.min_second_axis_rotation_rad = options.min_hand_eye_second_axis_rotation_rad;
    const HandEyeRotationResult hand_eye =
        EstimateHandEyeRotation(R_ck_ck1, R_sk_sk1, hand_eye_options);
    result.hand_eye_second_axis_ratio = hand_eye.second_axis_ratio;
    if (!hand_eye.ok) {
      result.message = hand_eye.message;
      return result;
    }
    R_cam_imu = hand_eye.R_cam_imu;
  }

  // Step 2: gyro bias (and the rotation, refined jointly).
  const GyroBiasEstimate bias =
      EstimateGyroBias(imu, frames, R_cam_imu, options.estimate_rotation_extrinsic, options);
  result.gyro_bias = bias.gyro_bias;
  result.R_cam_imu = bias.R_cam_imu;
  result.gyro_bias_iterations = bias.iterations;
  result.rms_rotation_residual_rad = bias.rms_rotation_residual_rad;
  if (!bias.converged) {
    result.message = StringPrintf(
        "the gyro bias did not converge in %d iterations (rotation residual "
        "%.3g rad RMS): the camera rotations do not match the gyro (check "
        "T_cam_imu, the time offset and the gyro units)",
        bias.iterations,
        bias.rms_rotation_residual_rad);
    return result;
  }

  // Step 3: linear alignment with free gravity.
  const SE3d T_cam_imu(bias.R_cam_imu, options.T_cam_imu.translation());
  const AlignmentProblem problem(
      imu, frames, T_cam_imu, bias.gyro_bias, options.accel_bias, noise, options.camera_noise);
  const AlignmentSolution free = problem.SolveFreeGravity();
  result.free_gravity_c0 = free.gravity_c0;
  result.free_scale = free.scale;
  result.free_scale_std = free.scale_std;
  result.free_condition_number = free.condition_number;
  const std::string excitation_advice =
      "the motion does not determine scale and gravity (it needs changes of acceleration and "
      "rotation, e.g. a figure eight; constant velocity or a pure rotation is not enough)";
  result.condition_number = free.condition_number;
  if (!(result.condition_number <= options.max_condition_number)) {
    result.message = StringPrintf("not enough excitation: condition number %.3g exceeds %.3g; ",
                                  result.condition_number,
                                  options.max_condition_number) +
                     excitation_advice;
    return result;
  }
  if (!(free.scale > 0.0)) {
    result.message = StringPrintf(
        "the scale came out %s (%.6g): the camera trajectory does not match "
        "the IMU motion (check that the poses are T_c0_c and not their "
        "inverses, T_cam_imu, and the time offset)",
        free.scale < 0.0 ? "negative" : "zero",
        free.scale);
    return result;
  }
  const double norm_error = std::abs(free.gravity_c0.norm() - G);
  if (!(norm_error <= options.max_gravity_norm_error_m_s2)) {
    result.message = StringPrintf(
                         "the gravity estimated without its known norm is %.4g m/s^2, %.3g "
                         "m/s^2 from the expected %.4g m/s^2 (allowed %.3g): ",
                         free.gravity_c0.norm(),
                         norm_error,
                         G,
                         options.max_gravity_norm_error_m_s2) +
                     "check the accelerometer units, --gravity, T_cam_imu and the time offset";
    return result;
  }

  // Step 4: refinement on the sphere |g| = G.
  const AlignmentSolution refined =
      problem.RefineGravity(free, G, options.gravity_tolerance_rad, options.max_gravity_iterations);
  result.iterations = refined.iterations;
  result.refined_condition_number = refined.condition_number;
  if (!std::isfinite(refined.condition_number)) {
    result.message = "the refined system is singular; " + excitation_advice;
    return result;
  }
  if (!refined.converged) {
    result.message = StringPrintf("the gravity refinement did not converge in %d iterations",
                                  refined.iterations);
    return result;
  }
  if (!(refined.scale > 0.0)) {
    result.message = StringPrintf(
        "the refined scale came out %.6g (not positive): the camera "
        "trajectory does not match the IMU motion",
        refined.scale);
    return result;
  }

  // Step 5: the uncertainty checks (align.h, equation (2)).
  result.scale_std = refined.scale_std;
  result.residual_noise_ratio = refined.residual_noise_ratio;
  const AlignmentSolution with_bias = problem.SolveFreeGravityWithAccelBias();
  result.scale_with_accel_bias = with_bias.scale;
  result.scale_with_accel_bias_std = with_bias.scale_std;
  result.accel_bias_estimate = with_bias.accel_bias;
  result.accel_bias_estimate_std = with_bias.accel_bias_std;
  if (!internal::CheckUncertainty(free, refined, with_bias, options, &result)) return result;

  // Step 6: the gravity-aligned world.
  result.scale = refined.scale;
  result.gravity_c0 = refined.gravity_c0;
  result.R_w_c0 = GravityAlignedRotation(refined.gravity_c0);
  result.states_w.reserve(frames.size());
  for (size_t k = 0; k < frames.size(); ++k) {
    const AlignmentFrame& frame = frames[k];
    GroundTruthState state;
    state.t_ns = frame.t_ns;
    const SO3d R_c0_s = frame.R_c0_c * T_cam_imu.so3();
    const Eigen::Vector3d p_c0_s =
        refined.scale * frame.p_c0_c + frame.R_c0_c * T_cam_imu.translation();
    state.q_w_s = (result.R_w_c0 * R_c0_s).quaternion();
    state.p_w_s = result.R_w_c0 * p_c0_s;
    state.v_w = result.R_w_c0 * refined.v_c0[k];
    state.gyro_bias = result.gyro_bias;
    state.accel_bias = options.accel_bias;
    result.states_w.push_back(state);
  }
  result.success = true;
  result.message = StringPrintf(
      "aligned %d camera frames: scale %.6g, gravity refined in %d "
      "iterations, condition number %.3g",
      static_cast<int>(frames.size()),
      result.scale,
      result.iterations,
      result.condition_number);
  result.message += StringPrintf(", scale std %.2g", result.scale_std);
  if (result.num_ignored_frames > 0) {
    result.message += StringPrintf("; %d camera poses outside the IMU data were ignored",
                                   result.num_ignored_frames);
  }
  return result;
}

}  // namespace splinecal
