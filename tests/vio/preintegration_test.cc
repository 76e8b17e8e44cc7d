#include "splinecal/vio/preintegration.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <random>
#include <vector>

#include "splinecal/error.h"
#include "splinecal/sim/noise_generator.h"
#include "splinecal/sim/trajectories.h"
#include "testing/numeric_diff.h"

namespace splinecal {
namespace {

using ::testing::HasSubstr;

constexpr double kGravity = 9.81;
constexpr int64_t kStartNs = 1403715273000000000;

// Readings of an analytic trajectory (exact derivatives, no noise) at `rate_hz`, plus biases.
std::vector<ImuSample> Readings(const AnalyticTrajectory& trajectory,
                                double rate_hz,
                                double duration_s,
                                const Eigen::Vector3d& gyro_bias = Eigen::Vector3d::Zero(),
                                const Eigen::Vector3d& accel_bias = Eigen::Vector3d::Zero()) {
  const Eigen::Vector3d g_w(0.0, 0.0, -kGravity);
  const int64_t step_ns = static_cast<int64_t>(1e9 / rate_hz + 0.5);
  const int n = static_cast<int>(duration_s * rate_hz + 0.5) + 1;
  std::vector<ImuSample> imu(n);
  for (int k = 0; k < n; ++k) {
    const TrajectoryState state = trajectory.Evaluate(k * step_ns * 1e-9);
    imu[k].t_ns = kStartNs + k * step_ns;
    imu[k].gyro = state.w_s + gyro_bias;
    imu[k].accel = state.T_w_s.so3().inverse() * (state.a_w - g_w) + accel_bias;
  }
  return imu;
}

struct RelativeMotion {
  SO3d delta_R;
  Eigen::Vector3d delta_v;
  Eigen::Vector3d delta_p;
};

// What the preintegration should give for the true trajectory between t_i and t_j
// (vio/preintegration.h): dR = R_i^T R_j, dv = R_i^T (v_j - v_i - g T),
// dp = R_i^T (p_j - p_i - v_i T - g T^2 / 2).
RelativeMotion TrueRelativeMotion(const AnalyticTrajectory& trajectory, double t_i, double t_j) {
  const Eigen::Vector3d g_w(0.0, 0.0, -kGravity);
  const TrajectoryState a = trajectory.Evaluate(t_i);
  const TrajectoryState b = trajectory.Evaluate(t_j);
  const double T = t_j - t_i;
  const SO3d R_i_inv = a.T_w_s.so3().inverse();
  RelativeMotion m;
  m.delta_R = R_i_inv * b.T_w_s.so3();
  m.delta_v = R_i_inv * (b.v_w - a.v_w - g_w * T);
  m.delta_p =
      R_i_inv * (b.T_w_s.translation() - a.T_w_s.translation() - a.v_w * T - 0.5 * T * T * g_w);
  return m;
}

struct Errors {
  double rotation;
  double velocity;
  double position;
};

Errors PreintegrationErrors(const AnalyticTrajectory& trajectory, double rate_hz, double T) {
  const std::vector<ImuSample> imu = Readings(trajectory, rate_hz, T + 0.1);
  const int64_t t_end_ns = kStartNs + static_cast<int64_t>(T * 1e9 + 0.5);
  const ImuPreintegration pre = Preintegrate(
      imu, kStartNs, t_end_ns, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), nullptr);
  const RelativeMotion truth = TrueRelativeMotion(trajectory, 0.0, T);
  return {(truth.delta_R.inverse() * pre.delta_R).Log().norm(),
          (truth.delta_v - pre.delta_v).norm(),
          (truth.delta_p - pre.delta_p).norm()};
}

// The midpoint scheme is second order: halving the step divides the error by ~4.
TEST(Preintegrate, ConvergesToTheContinuousMotionAtSecondOrder) {
  const AnalyticTrajectory trajectory = Figure8Trajectory();
  for (double T : {0.1, 1.0}) {
    const Errors e200 = PreintegrationErrors(trajectory, 200.0, T);
    const Errors e400 = PreintegrationErrors(trajectory, 400.0, T);
    SCOPED_TRACE(T);
    // Figure eight: rates <= 0.63 rad/s, accelerations <= 2.4 m/s^2. The position step's error
    // is j h^3 / 12 per step for a jerk j (trapezoidal acceleration with h^2/2), so it grows as
    // j h^2 T / 12, like the velocity's. Measured: 1.5e-8 rad, 1.1e-8 m/s, 2.8e-7 m at 0.1 s;
    // 1.3e-7 rad, 1.0e-6 m/s, 2.3e-6 m at 1 s. Bounds with >= 3x margin.
    EXPECT_LT(e200.rotation, 1e-6 * T);
    EXPECT_LT(e200.velocity, 1e-5 * T);
    EXPECT_LT(e200.position, 1e-5 * T);
    for (auto [a, b] : {std::pair{e200.rotation, e400.rotation},
                        std::pair{e200.velocity, e400.velocity},
                        std::pair{e200.position, e400.position}}) {
      EXPECT_GT(a / b, 3.5);
      EXPECT_LT(a / b, 4.5);
    }
  }
}

// World-frame midpoint integration of the same readings is reproduced to rounding: the
// relations R_j = R_i dR, v_j = v_i + g T + R_i dv, p_j = ... hold exactly for the discrete
// scheme (the property the alignment's noise-free tests rely on).
TEST(Preintegrate, ExactForTheDiscreteWorldTrajectory) {
  const AnalyticTrajectory trajectory = RandomTrajectory(7);
  const Eigen::Vector3d bg(0.01, -0.02, 0.03), ba(0.1, 0.05, -0.2);
  const std::vector<ImuSample> imu = Readings(trajectory, 200.0, 2.0, bg, ba);
  const Eigen::Vector3d g_w(0.0, 0.0, -kGravity);
  const TrajectoryState s0 = trajectory.Evaluate(0.0);
  SO3d R = s0.T_w_s.so3();
  Eigen::Vector3d p = s0.T_w_s.translation(), v = s0.v_w;
  const double h = 1.0 / 200.0;
  const int i = 37, j = 311;  // any two samples
  SO3d R_i;
  Eigen::Vector3d p_i = Eigen::Vector3d::Zero(), v_i = Eigen::Vector3d::Zero();
  for (int k = 0; k < j; ++k) {
    if (k == i) {
      R_i = R;
      p_i = p;
      v_i = v;
    }
    const SO3d R1 = R * SO3d::Exp((0.5 * (imu[k].gyro + imu[k + 1].gyro) - bg) * h);
    const Eigen::Vector3d a = 0.5 * (R * (imu[k].accel - ba) + R1 * (imu[k + 1].accel - ba)) + g_w;
    p += v * h + 0.5 * h * h * a;
    v += a * h;
    R = R1;
  }
  const ImuPreintegration pre = Preintegrate(imu, imu[i].t_ns, imu[j].t_ns, bg, ba, nullptr);
  const double T = (j - i) * h;
  EXPECT_NEAR(pre.dt_s, T, 1e-15);
  EXPECT_LT((R_i * pre.delta_R).inverse().operator*(R).Log().norm(), 1e-13);
  EXPECT_LT((v_i + g_w * T + R_i * pre.delta_v - v).norm(), 1e-12);
  EXPECT_LT((p_i + v_i * T + 0.5 * T * T * g_w + R_i * pre.delta_p - p).norm(), 1e-12);
}

// Splitting an interval at a sample composes exactly; at a time between samples (interpolated
// reading) to O(h^3) per split.
TEST(Preintegrate, ComposesOverSplitIntervals) {
  const AnalyticTrajectory trajectory = Figure8Trajectory();
  const std::vector<ImuSample> imu = Readings(trajectory, 200.0, 1.0);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const int64_t t0 = imu[3].t_ns, t2 = imu[150].t_ns;
  const ImuPreintegration whole = Preintegrate(imu, t0, t2, zero, zero, nullptr);
  for (int64_t t1 : {imu[77].t_ns, imu[77].t_ns + 1234567}) {
    const ImuPreintegration a = Preintegrate(imu, t0, t1, zero, zero, nullptr);
    const ImuPreintegration b = Preintegrate(imu, t1, t2, zero, zero, nullptr);
    const SO3d dR = a.delta_R * b.delta_R;
    const Eigen::Vector3d dv = a.delta_v + a.delta_R * b.delta_v;
    const Eigen::Vector3d dp = a.delta_p + a.delta_v * b.dt_s + a.delta_R * b.delta_p;
    const bool at_sample = t1 == imu[77].t_ns;
    const double tolerance = at_sample ? 1e-13 : 1e-7;
    SCOPED_TRACE(at_sample);
    EXPECT_LT((whole.delta_R.inverse() * dR).Log().norm(), tolerance);
    EXPECT_LT((whole.delta_v - dv).norm(), tolerance);
    EXPECT_LT((whole.delta_p - dp).norm(), tolerance);
  }
}

struct BiasCase {
  Eigen::Vector3d bg;
  Eigen::Vector3d ba;
};

// Every bias Jacobian against central differences of a re-integration (right perturbation of dR).
TEST(Preintegrate, BiasJacobiansMatchNumericDerivatives) {
  const AnalyticTrajectory trajectory = RandomTrajectory(3);
  const std::vector<ImuSample> imu = Readings(trajectory, 200.0, 1.5);
  // Tiny, generic and large biases; 0.1 s (a camera interval) and 1.2 s.
  const std::vector<BiasCase> cases = {
      {Eigen::Vector3d(1e-9, -1e-9, 2e-9), Eigen::Vector3d(1e-9, 0.0, -1e-9)},
      {Eigen::Vector3d(0.01, -0.02, 0.015), Eigen::Vector3d(0.1, -0.05, 0.2)},
      {Eigen::Vector3d(0.5, -0.3, 0.4), Eigen::Vector3d(1.0, 2.0, -1.5)}};
  for (const BiasCase& c : cases) {
    for (int64_t t1 : {imu[40].t_ns + 3000000, imu[263].t_ns}) {
      const int64_t t0 = imu[20].t_ns + 3000000;  // between samples: interpolated readings
      const ImuPreintegration pre = Preintegrate(imu, t0, t1, c.bg, c.ba, nullptr);
      const auto dR_of_bg = [&](const Eigen::Vector3d& bg) -> Eigen::Vector3d {
        return (pre.delta_R.inverse() * Preintegrate(imu, t0, t1, bg, c.ba, nullptr).delta_R).Log();
      };
      const auto dv_of = [&](const Eigen::Vector3d& bg, const Eigen::Vector3d& ba) {
        return Preintegrate(imu, t0, t1, bg, ba, nullptr).delta_v;
      };
      const auto dp_of = [&](const Eigen::Vector3d& bg, const Eigen::Vector3d& ba) {
        return Preintegrate(imu, t0, t1, bg, ba, nullptr).delta_p;
      };
      const Eigen::Matrix3d J_dR_bg = testing::CentralDifferenceJacobian(dR_of_bg, c.bg);
      const Eigen::Matrix3d J_dv_bg = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector3d& bg) -> Eigen::Vector3d { return dv_of(bg, c.ba); }, c.bg);
      const Eigen::Matrix3d J_dv_ba = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector3d& ba) -> Eigen::Vector3d { return dv_of(c.bg, ba); }, c.ba);
      const Eigen::Matrix3d J_dp_bg = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector3d& bg) -> Eigen::Vector3d { return dp_of(bg, c.ba); }, c.bg);
      const Eigen::Matrix3d J_dp_ba = testing::CentralDifferenceJacobian(
          [&](const Eigen::Vector3d& ba) -> Eigen::Vector3d { return dp_of(c.bg, ba); }, c.ba);
      // Central differences with h = 1e-5 on O(1) functions: ~1e-10 error (numeric_diff.h).
      constexpr double kTolerance = 1e-8;
      SCOPED_TRACE(c.bg.transpose());
      EXPECT_TRUE(pre.J_dR_bg.isApprox(J_dR_bg, kTolerance)) << pre.J_dR_bg << "\n" << J_dR_bg;
      EXPECT_TRUE(pre.J_dv_bg.isApprox(J_dv_bg, kTolerance)) << pre.J_dv_bg << "\n" << J_dv_bg;
      EXPECT_TRUE(pre.J_dv_ba.isApprox(J_dv_ba, kTolerance)) << pre.J_dv_ba << "\n" << J_dv_ba;
      EXPECT_TRUE(pre.J_dp_bg.isApprox(J_dp_bg, kTolerance)) << pre.J_dp_bg << "\n" << J_dp_bg;
      EXPECT_TRUE(pre.J_dp_ba.isApprox(J_dp_ba, kTolerance)) << pre.J_dp_ba << "\n" << J_dp_ba;
    }
  }
}

// The first-order correction's error shrinks with the square of the bias change.
TEST(Preintegrate, FirstOrderBiasCorrectionIsSecondOrderAccurate) {
  const AnalyticTrajectory trajectory = Figure8Trajectory();
  const std::vector<ImuSample> imu = Readings(trajectory, 200.0, 1.0);
  const Eigen::Vector3d bg0(0.01, 0.0, -0.01), ba0(0.05, 0.02, 0.0);
  const ImuPreintegration pre = Preintegrate(imu, imu[0].t_ns, imu[100].t_ns, bg0, ba0, nullptr);
  const Eigen::Vector3d dir_g(0.6, -0.8, 0.3), dir_a(-0.2, 0.5, 0.9);
  double previous[3] = {0.0, 0.0, 0.0};
  for (double delta : {1e-2, 1e-3}) {
    const Eigen::Vector3d bg = bg0 + delta * dir_g, ba = ba0 + delta * dir_a;
    const ImuPreintegration exact = Preintegrate(imu, imu[0].t_ns, imu[100].t_ns, bg, ba, nullptr);
    const double e[3] = {(exact.delta_R.inverse() * pre.CorrectedDeltaR(bg)).Log().norm(),
                         (exact.delta_v - pre.CorrectedDeltaV(bg, ba)).norm(),
                         (exact.delta_p - pre.CorrectedDeltaP(bg, ba)).norm()};
    for (int i = 0; i < 3; ++i) {
      EXPECT_LT(e[i], 10.0 * delta * delta) << i;
      if (previous[i] > 0.0) {
        EXPECT_GT(previous[i] / e[i], 70.0) << i;  // ~100 for a second-order remainder
        EXPECT_LT(previous[i] / e[i], 130.0) << i;
      }
      previous[i] = e[i];
    }
  }
}

TEST(PreintegrateRotation, MatchesTheFullPreintegration) {
  const std::vector<ImuSample> imu = Readings(RandomTrajectory(2), 200.0, 1.0);
  const Eigen::Vector3d bg(0.02, -0.01, 0.005);
  const int64_t t0 = imu[5].t_ns + 1000, t1 = imu[60].t_ns - 7000;
  const ImuPreintegration pre = Preintegrate(imu, t0, t1, bg, Eigen::Vector3d::Zero(), nullptr);
  Eigen::Matrix3d J;
  const SO3d dR = PreintegrateRotation(imu, t0, t1, bg, &J);
  EXPECT_LT((pre.delta_R.inverse() * dR).Log().norm(), 1e-15);
  EXPECT_LT((pre.J_dR_bg - J).norm(), 1e-15);
  EXPECT_LT((PreintegrateRotation(imu, t0, t1, bg, nullptr).inverse() * dR).Log().norm(), 1e-15);
}

// ---------------------------------------------------------------------------------------------
// Covariance

using Matrix9d = Eigen::Matrix<double, 9, 9>;

// Empirical covariance of [dp, dv, dphi] over `runs` noisy copies of the readings.
Matrix9d MonteCarloCovariance(
    const std::vector<ImuSample>& clean, const ImuNoise& noise, int64_t t0, int64_t t1, int runs) {
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const ImuPreintegration truth = Preintegrate(clean, t0, t1, zero, zero, nullptr);
  Matrix9d sum = Matrix9d::Zero();
  for (int run = 0; run < runs; ++run) {
    std::vector<ImuSample> noisy = clean;
    ImuNoiseGenerator generator(noise, zero, zero, 1000 + run);
    for (ImuSample& sample : noisy) generator.Corrupt(&sample, nullptr, nullptr);
    const ImuPreintegration pre = Preintegrate(noisy, t0, t1, zero, zero, nullptr);
    Eigen::Matrix<double, 9, 1> e;
    e << pre.delta_p - truth.delta_p, pre.delta_v - truth.delta_v,
        (truth.delta_R.inverse() * pre.delta_R).Log();
    sum += e * e.transpose();
  }
  return sum / runs;
}

// Compares the diagonal blocks' traces (statistical tolerance for `runs` draws).
void ExpectCovarianceMatches(const Matrix9d& predicted, const Matrix9d& empirical, double tol) {
  for (int block = 0; block < 3; ++block) {
    const double p = predicted.block<3, 3>(3 * block, 3 * block).trace();
    const double e = empirical.block<3, 3>(3 * block, 3 * block).trace();
    EXPECT_NEAR(e / p, 1.0, tol) << "block " << block << ": predicted " << p << " empirical " << e;
  }
  // The whole matrix, in the metric of the prediction: tr(P^-1 E) / 9 ~ 1.
  const double normalised = (predicted.ldlt().solve(empirical)).trace() / 9.0;
  EXPECT_NEAR(normalised, 1.0, tol);
}

TEST(PreintegrateCovariance, MatchesMonteCarloWhiteNoise) {
  const std::vector<ImuSample> clean = Readings(Figure8Trajectory(), 200.0, 0.5);
  ImuNoise noise;  // ADIS16448 densities, random walks made negligible
  noise.gyroscope_random_walk = 1e-12;
  noise.accelerometer_random_walk = 1e-12;
  const int64_t t0 = clean[10].t_ns, t1 = clean[50].t_ns;  // 0.2 s, 40 steps
  const ImuPreintegration pre =
      Preintegrate(clean, t0, t1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &noise);
  ASSERT_TRUE(pre.has_covariance);
  // 4000 draws: the trace of a 3x3 block is known to ~sqrt(2/(3*4000)) = 1.3%; midpoint
  // averaging of neighbouring samples lowers the true variance by 1/(2N) = 1.3%. 6% bound.
  const Matrix9d empirical = MonteCarloCovariance(clean, noise, t0, t1, 4000);
  ExpectCovarianceMatches(pre.covariance.topLeftCorner<9, 9>(), empirical, 0.06);
}

TEST(PreintegrateCovariance, MatchesMonteCarloWithBiasRandomWalk) {
  const std::vector<ImuSample> clean = Readings(Figure8Trajectory(), 200.0, 1.5);
  ImuNoise noise;
  noise.gyroscope_noise_density = 1e-5;  // random walk dominant: 100x the EuRoC value
  noise.accelerometer_noise_density = 1e-4;
  noise.gyroscope_random_walk = 2e-3;
  noise.accelerometer_random_walk = 0.3;
  const int64_t t0 = clean[0].t_ns, t1 = clean[200].t_ns;  // 1 s
  const ImuPreintegration pre =
      Preintegrate(clean, t0, t1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &noise);
  // The random walk's share of the covariance must be right, not only the white part.
  ImuNoise white_only = noise;
  white_only.gyroscope_random_walk = 1e-12;
  white_only.accelerometer_random_walk = 1e-12;
  const ImuPreintegration white =
      Preintegrate(clean, t0, t1, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), &white_only);
  const double velocity_variance = pre.covariance.block<3, 3>(kPreintV, kPreintV).trace();
  const double white_velocity_variance = white.covariance.block<3, 3>(kPreintV, kPreintV).trace();
  ASSERT_GT(velocity_variance, 10.0 * white_velocity_variance);
  const Matrix9d empirical = MonteCarloCovariance(clean, noise, t0, t1, 4000);
  // The generator's first sample uses the initial bias, so the walk starts one step late:
  // 1/200 of the interval. Same 6% bound as above.
  ExpectCovarianceMatches(pre.covariance.topLeftCorner<9, 9>(), empirical, 0.06);
}

// Continuous-time densities: the covariance does not depend on the sampling rate.
TEST(PreintegrateCovariance, IndependentOfTheImuRate) {
  const ImuNoise noise;
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  const AnalyticTrajectory trajectory = Figure8Trajectory();
  const std::vector<ImuSample> imu200 = Readings(trajectory, 200.0, 1.0);
  const std::vector<ImuSample> imu800 = Readings(trajectory, 800.0, 1.0);
  const ImuPreintegration a =
      Preintegrate(imu200, kStartNs, kStartNs + 500000000, zero, zero, &noise);
  const ImuPreintegration b =
      Preintegrate(imu800, kStartNs, kStartNs + 500000000, zero, zero, &noise);
  // The per-step linearisation differs at O(h): 1% bound.
  EXPECT_LT((a.covariance - b.covariance).norm(), 0.01 * a.covariance.norm());
  // Symmetric positive definite.
  EXPECT_LT((a.covariance - a.covariance.transpose()).norm(), 1e-15 * a.covariance.norm());
  const Eigen::LLT<Eigen::Matrix<double, 15, 15>> llt(a.covariance);
  EXPECT_EQ(llt.info(), Eigen::Success);
  // Closed forms for the bias blocks: a random walk for T = 0.5 s.
  EXPECT_NEAR(a.covariance(kPreintBg, kPreintBg),
              noise.gyroscope_random_walk * noise.gyroscope_random_walk * 0.5,
              1e-20);
  EXPECT_NEAR(a.covariance(kPreintBa + 2, kPreintBa + 2),
              noise.accelerometer_random_walk * noise.accelerometer_random_walk * 0.5,
              1e-18);
}

TEST(Preintegrate, NoCovarianceWithoutNoise) {
  const std::vector<ImuSample> imu = Readings(Figure8Trajectory(), 200.0, 0.2);
  const ImuPreintegration pre = Preintegrate(
      imu, imu[0].t_ns, imu[10].t_ns, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), nullptr);
  EXPECT_FALSE(pre.has_covariance);
  EXPECT_EQ(pre.covariance.norm(), 0.0);
}

// ---------------------------------------------------------------------------------------------

TEST(Preintegrate, RefusesEmptyIntervalsAndIntervalsOutsideTheData) {
  const std::vector<ImuSample> imu = Readings(Figure8Trajectory(), 200.0, 0.2);
  const Eigen::Vector3d zero = Eigen::Vector3d::Zero();
  EXPECT_THROW(Preintegrate(imu, imu[5].t_ns, imu[5].t_ns, zero, zero, nullptr), Error);
  EXPECT_THROW(Preintegrate(imu, imu[5].t_ns, imu[4].t_ns, zero, zero, nullptr), Error);
  try {
    Preintegrate(imu, imu[0].t_ns - 1, imu[4].t_ns, zero, zero, nullptr);
    FAIL() << "expected an Error";
  } catch (const Error& error) {
    EXPECT_THAT(error.what(), HasSubstr("is not inside the IMU data"));
  }
  EXPECT_THROW(PreintegrateRotation(imu, imu[0].t_ns, imu.back().t_ns + 1, zero, nullptr), Error);
  EXPECT_THROW(Preintegrate({imu[0]}, imu[0].t_ns, imu[0].t_ns + 1, zero, zero, nullptr), Error);
  // The whole data is fine.
  EXPECT_NO_THROW(Preintegrate(imu, imu.front().t_ns, imu.back().t_ns, zero, zero, nullptr));
}

TEST(InterpolateImu, ExactAtSamplesLinearBetweenThrowsOutside) {
  std::vector<ImuSample> imu(3);
  for (int k = 0; k < 3; ++k) {
    imu[k].t_ns = 1000 + 10 * k;
    imu[k].gyro = Eigen::Vector3d(0.1 * k, 1.0 / 3.0 + k, -k);
    imu[k].accel = Eigen::Vector3d(9.81, 0.7 * k * k, 0.1);
  }
  for (int k = 0; k < 3; ++k) {
    const ImuSample s = InterpolateImu(imu, imu[k].t_ns);
    EXPECT_EQ(s.gyro, imu[k].gyro);  // bit-exact
    EXPECT_EQ(s.accel, imu[k].accel);
  }
  const ImuSample mid = InterpolateImu(imu, 1013);
  EXPECT_EQ(mid.t_ns, 1013);
  EXPECT_LT((mid.gyro - (0.7 * imu[1].gyro + 0.3 * imu[2].gyro)).norm(), 1e-15);
  EXPECT_LT((mid.accel - (0.7 * imu[1].accel + 0.3 * imu[2].accel)).norm(), 1e-14);
  EXPECT_THROW(InterpolateImu(imu, 999), Error);
  EXPECT_THROW(InterpolateImu(imu, 1021), Error);
  EXPECT_THROW(InterpolateImu({}, 1000), Error);
}

}  // namespace
}  // namespace splinecal
