#include "splinecal/calib/fit.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "calib/fit_test_data.h"
#include "splinecal/error.h"
#include "splinecal/spline/trajectory_model.h"
#include "splinecal/units.h"
#include "testing/autodiff_costs.h"
#include "testing/rotations.h"
#include "testing/trajectory_models.h"

namespace splinecal {
namespace {

using testing::AngleDeg;
using ::testing::AllOf;
using testing::FitData;
using testing::FitScenario;
using ::testing::HasSubstr;
using testing::MakeFitData;
using testing::PerturbedControlPoses;

// The noise-free recovery bounds (docs/fit.md, "Results"). Noise-free data generated from a spline
// with the same knots is fitted exactly: the minimum has zero cost, and the solver stops at cost
// ~1e-17 where parameter errors are ~1e-11.
constexpr double kNoiseFreeControlPoseTolerance = 1e-6;  // |Log(T_true^-1 T)| [m, rad]
constexpr double kNoiseFreeBiasTolerance = 1e-8;         // [rad/s, m/s^2]
constexpr double kNoiseFreeGravityToleranceDeg = 1e-6;
// "Within 3 reported standard deviations" (issue).
constexpr double kSigmaBound = 3.0;
// Two ways of computing the same objective reach the same minimum; the solver's tolerances
// (function 1e-10 relative) bound the difference of the final costs, and the estimates differ by
// well below their standard deviations (~1e-5 and up).
constexpr double kSameSolutionCostTolerance = 1e-8;  // relative
constexpr double kSameSolutionBiasTolerance = 1e-7;

double MaxControlPoseError(const SE3Splined& truth, const std::vector<SE3d>& fitted) {
  EXPECT_EQ(static_cast<int>(fitted.size()), truth.num_control_poses());
  double worst = 0.0;
  for (size_t i = 0; i < fitted.size(); ++i) {
    worst = std::max(worst, (truth.control_pose(i).inverse() * fitted[i]).Log().norm());
  }
  return worst;
}

FitOptions QuietOptions() {
  FitOptions options;
  options.model.knot_spacing_s = 0.1;
  options.keep_samples = false;
  return options;
}

TEST(Fit, RecoversNoiseFreeSimulationFromAPerturbedStart) {
  FitScenario scenario;
  scenario.R_world = SO3d::Exp(Eigen::Vector3d(0.2, -0.3, 0.5));  // gravity not along -z
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.covariance.compute = false;
  FitProblem problem(data.imu, data.poses, options);
  ASSERT_EQ(problem.layout().t0_ns, data.truth.t0_ns());
  ASSERT_EQ(problem.layout().num_control_poses, data.truth.num_control_poses());
  // Centimetres and degrees off, biases zero, gravity 2 degrees off.
  problem.SetControlPoses(PerturbedControlPoses(data.truth, 0.02, 0.035, 17));
  problem.SetBiases(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  problem.SetGravity(SO3d::Exp(Eigen::Vector3d(0.035, 0.0, 0.0)) * data.gravity_w);
  const FitResult result = problem.Solve();
  EXPECT_LE(MaxControlPoseError(data.truth, result.control_poses), kNoiseFreeControlPoseTolerance);
  EXPECT_LE((result.gyro_bias - scenario.gyro_bias).cwiseAbs().maxCoeff(), kNoiseFreeBiasTolerance);
  EXPECT_LE((result.accel_bias - scenario.accel_bias).cwiseAbs().maxCoeff(),
            kNoiseFreeBiasTolerance);
  // The direction is what the fit estimates; |g_w| is fixed by the GravityManifold.
  EXPECT_LE(AngleDeg(result.gravity_w, data.gravity_w), kNoiseFreeGravityToleranceDeg);
}

TEST(Fit, NoisyEstimatesLieWithinThreeReportedStandardDeviations) {
  FitScenario scenario;
  scenario.duration_s = 30.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  std::mt19937_64 rng(21);
  std::normal_distribution<double> normal(0.0, 1.0);
  for (int a = 0; a < 3; ++a) {
    scenario.gyro_bias[a] = 0.01 * normal(rng);
    scenario.accel_bias[a] = 0.1 * normal(rng);
  }
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise = scenario.noise;
  const FitResult result = Fit(data.imu, data.poses, options);
  ASSERT_TRUE(result.covariance_ok);
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(std::abs(result.gyro_bias[a] - scenario.gyro_bias[a]),
              kSigmaBound * result.gyro_bias_std[a])
        << "axis " << a;
    EXPECT_LE(std::abs(result.accel_bias[a] - scenario.accel_bias[a]),
              kSigmaBound * result.accel_bias_std[a])
        << "axis " << a;
  }
  EXPECT_LE(AngleDeg(result.gravity_w, data.gravity_w),
            kSigmaBound * result.gravity_direction_std_deg);
  // Consistent noise: residuals at the noise level, no warnings.
  EXPECT_NEAR(result.residual_rms.gyro_rad_s / result.noise_std.gyro_rad_s, 1.0, 0.05);
  EXPECT_NEAR(result.residual_rms.accel_m_s2 / result.noise_std.accel_m_s2, 1.0, 0.05);
  EXPECT_THAT(result.warnings, ::testing::IsEmpty());
}

// Both trajectory models (FitOptions::model.trajectory), each on data simulated from a truth
// spline of its own model.
class FitOfModel : public ::testing::TestWithParam<TrajectoryModel> {};

TEST_P(FitOfModel, RecoversTimeOffsetAndExtrinsicWithinThreeStandardDeviations) {
  FitScenario scenario;
  scenario.truth_model = GetParam();
  scenario.duration_s = 30.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  scenario.pose_rate_hz = 20.0;
  scenario.time_offset_s = 0.005;  // 5 ms
  const Eigen::Vector3d axis = Eigen::Vector3d(1.0, 2.0, -1.0).normalized();
  scenario.T_m_s = SE3d(SO3d::Exp(5.0 / kRadToDeg * axis),    // 5 degrees
                        Eigen::Vector3d(0.06, -0.05, 0.06));  // ~10 cm
  const FitData data = MakeFitData(scenario);
  ASSERT_EQ(data.truth.model(), GetParam());
  FitOptions options = QuietOptions();
  options.model.trajectory = GetParam();
  options.model.noise = scenario.noise;
  options.estimate_time_offset = true;
  options.estimate_extrinsic = true;
  const FitResult result = Fit(data.imu, data.poses, options);
  ASSERT_TRUE(result.covariance_ok);
  EXPECT_EQ(result.trajectory, GetParam());
  EXPECT_EQ(result.MakeSpline().model(), GetParam());
  EXPECT_LE(std::abs(result.time_offset_s - scenario.time_offset_s),
            kSigmaBound * result.time_offset_std_s);
  // Errors in the tangent of T_m_s (right perturbation): rho = R^T dt, phi = Log(R^T R').
  const SE3d& truth = scenario.T_m_s;
  const Eigen::Vector3d rho =
      truth.so3().inverse() * (result.T_m_s.translation() - truth.translation());
  const Eigen::Vector3d phi = (truth.so3().inverse() * result.T_m_s.so3()).Log();
  for (int a = 0; a < 3; ++a) {
    EXPECT_LE(std::abs(rho[a]), kSigmaBound * result.T_m_s_translation_std_m[a]);
    EXPECT_LE(std::abs(phi[a]), kSigmaBound * result.T_m_s_rotation_std_rad[a]);
    EXPECT_LE(std::abs(result.gyro_bias[a] - scenario.gyro_bias[a]),
              kSigmaBound * result.gyro_bias_std[a]);
    EXPECT_LE(std::abs(result.accel_bias[a] - scenario.accel_bias[a]),
              kSigmaBound * result.accel_bias_std[a]);
  }
  EXPECT_LE(AngleDeg(result.gravity_w, data.gravity_w),
            kSigmaBound * result.gravity_direction_std_deg);
  // The model matches the truth's: the accelerometer residuals are the simulated noise.
  EXPECT_NEAR(result.residual_rms.accel_m_s2 / result.noise_std.accel_m_s2, 1.0, 0.05);
  // This motion excites both: no "not determined" warnings.
  EXPECT_THAT(result.warnings, ::testing::IsEmpty());
}

INSTANTIATE_TEST_SUITE_P(Models,
                         FitOfModel,
                         testing::BothTrajectoryModels(),
                         testing::TrajectoryModelTestName);

// The split SO(3) x R^3 model end to end (FitOptions::model.trajectory): noise-free data from a
// split truth is fitted exactly from a perturbed start (the noisy case is FitOfModel above).
TEST(Fit, SplitModelRecoversASplitSplineSimulationExactly) {
  FitScenario scenario;
  scenario.truth_model = TrajectoryModel::kSplitSO3R3;
  scenario.R_world = SO3d::Exp(Eigen::Vector3d(0.2, -0.3, 0.5));
  const FitData data = MakeFitData(scenario);
  ASSERT_EQ(data.truth.model(), TrajectoryModel::kSplitSO3R3);
  FitOptions options = QuietOptions();
  options.model.trajectory = TrajectoryModel::kSplitSO3R3;
  options.covariance.compute = false;
  FitProblem problem(data.imu, data.poses, options);
  problem.SetControlPoses(PerturbedControlPoses(data.truth, 0.02, 0.035, 17));
  problem.SetBiases(Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero());
  problem.SetGravity(SO3d::Exp(Eigen::Vector3d(0.035, 0.0, 0.0)) * data.gravity_w);
  const FitResult result = problem.Solve();
  EXPECT_EQ(result.trajectory, TrajectoryModel::kSplitSO3R3);
  EXPECT_EQ(result.MakeSpline().model(), TrajectoryModel::kSplitSO3R3);
  EXPECT_LE(MaxControlPoseError(data.truth, result.control_poses), kNoiseFreeControlPoseTolerance);
  EXPECT_LE((result.gyro_bias - scenario.gyro_bias).cwiseAbs().maxCoeff(), kNoiseFreeBiasTolerance);
  EXPECT_LE((result.accel_bias - scenario.accel_bias).cwiseAbs().maxCoeff(),
            kNoiseFreeBiasTolerance);
  EXPECT_LE(AngleDeg(result.gravity_w, data.gravity_w), kNoiseFreeGravityToleranceDeg);
  // The coupled model cannot represent this truth exactly: its IMU residuals stay above zero.
  FitOptions coupled = options;
  coupled.model.trajectory = TrajectoryModel::kSE3;
  const FitResult other = Fit(data.imu, data.poses, coupled);
  EXPECT_GT(other.residual_rms.accel_m_s2, 100.0 * result.residual_rms.accel_m_s2);
}

TEST(Fit, ReattachesPoseResidualsWhenTheTimeOffsetCrossesKnots) {
  // Noise-free data with a 37 ms offset, solved from offset 0 (the correlation guess is
  // overridden): poses stamped within 37 ms before a knot change segment on the way, are
  // re-attached, and the offset is recovered exactly.
  constexpr double kOffsetTolerance = 1e-7;  // [s]; noise-free, solver tolerance ~1e-10
  FitScenario scenario;
  scenario.duration_s = 12.0;
  scenario.pose_rate_hz = 20.0;
  scenario.time_offset_s = 0.037;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.estimate_time_offset = true;
  options.covariance.compute = false;
  FitProblem problem(data.imu, data.poses, options);
  problem.SetTimeOffset(0.0);
  const FitResult result = problem.Solve();
  EXPECT_GE(result.solve.rounds, 2);
  EXPECT_NEAR(result.time_offset_s, scenario.time_offset_s, kOffsetTolerance);
  EXPECT_LE((result.gyro_bias - scenario.gyro_bias).cwiseAbs().maxCoeff(), 1e-7);
}

TEST(Fit, AutoDiffPerSampleUnsharedAndSchurPathsReachTheSameSolution) {
  FitScenario scenario;
  scenario.duration_s = 6.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise = scenario.noise;
  options.covariance.compute = false;
  const FitResult reference = Fit(data.imu, data.poses, options);
  std::vector<FitOptions> variants(4, options);
  variants[0].residuals.replacement = testing::AutoDiffReplacementCosts();
  variants[1].residuals.layout = ImuResidualLayout::kPerSample;
  variants[2].residuals.share_knot_caches = false;
  variants[3].solver.linear_solver = LinearSolver::kSparseSchur;
  for (const FitOptions& variant : variants) {
    const FitResult result = Fit(data.imu, data.poses, variant);
    EXPECT_NEAR(result.solve.final_cost,
                reference.solve.final_cost,
                kSameSolutionCostTolerance * reference.solve.final_cost);
    EXPECT_LE((result.gyro_bias - reference.gyro_bias).cwiseAbs().maxCoeff(),
              kSameSolutionBiasTolerance);
    EXPECT_LE((result.accel_bias - reference.accel_bias).cwiseAbs().maxCoeff(),
              kSameSolutionBiasTolerance);
  }
}

TEST(Fit, TheThreeCovarianceComputationsAgree) {
  // ceres::Covariance on the fit's problem, on the compressed problem, and the sparse Cholesky
  // of the compressed information compute the same (J^T J)^-1 block: equal to rounding times
  // the condition number (8 s of data leave the extrinsic translation weakly determined, and its
  // variance agrees to ~1e-8 only).
  constexpr double kSameCovarianceTolerance = 1e-6;  // relative to sqrt(C_rr C_cc)
  FitScenario scenario;
  scenario.duration_s = 8.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  scenario.pose_rate_hz = 20.0;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise = scenario.noise;
  options.estimate_time_offset = true;
  options.estimate_extrinsic = true;
  options.model.bias_model = BiasModel::kSpline;
  options.model.noise.gyroscope_random_walk = ImuNoise::Adis16448().gyroscope_random_walk;
  options.model.noise.accelerometer_random_walk = ImuNoise::Adis16448().accelerometer_random_walk;
  options.covariance.backend = CovarianceBackend::kCeresUncompressed;
  const FitResult direct = Fit(data.imu, data.poses, options);
  options.covariance.backend = CovarianceBackend::kAuto;
  const FitResult compressed = Fit(data.imu, data.poses, options);
  options.covariance.max_ceres_covariance_entries = 0.0;
  const FitResult cholesky = Fit(data.imu, data.poses, options);
  ASSERT_TRUE(direct.covariance_ok);
  ASSERT_TRUE(compressed.covariance_ok);
  ASSERT_TRUE(cholesky.covariance_ok);
  EXPECT_THAT(cholesky.covariance_method, HasSubstr("sparse LDL^T"));
  const Eigen::MatrixXd& C = direct.covariance;
  ASSERT_EQ(C.rows(), 8 + 1 + 6);
  for (const FitResult* other : {&compressed, &cholesky}) {
    for (int r = 0; r < C.rows(); ++r) {
      for (int c = 0; c < C.cols(); ++c) {
        const double scale = std::sqrt(C(r, r) * C(c, c));
        EXPECT_NEAR(other->covariance(r, c), C(r, c), kSameCovarianceTolerance * scale)
            << direct.covariance_labels[r] << ", " << direct.covariance_labels[c];
      }
    }
  }
}

TEST(Fit, BiasSplineFollowsADriftingBias) {
  FitScenario scenario;
  scenario.duration_s = 30.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  // 100x ADIS16448's random walk, so that the drift is far above the white-noise floor.
  scenario.noise.gyroscope_random_walk = 100.0 * ImuNoise::Adis16448().gyroscope_random_walk;
  scenario.noise.accelerometer_random_walk =
      100.0 * ImuNoise::Adis16448().accelerometer_random_walk;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise = scenario.noise;
  options.model.bias_model = BiasModel::kSpline;
  options.keep_samples = true;
  const FitResult spline_fit = Fit(data.imu, data.poses, options);
  options.model.bias_model = BiasModel::kConstant;
  const FitResult constant_fit = Fit(data.imu, data.poses, options);
  // The spline absorbs the drift: its residuals are at the white-noise level, the constant
  // model's are not.
  EXPECT_LT(spline_fit.residual_rms.gyro_rad_s / spline_fit.noise_std.gyro_rad_s, 1.05);
  EXPECT_GT(constant_fit.residual_rms.gyro_rad_s / constant_fit.noise_std.gyro_rad_s, 1.2);
  EXPECT_EQ(spline_fit.gyro_bias_control_points.size(),
            spline_fit.accel_bias_control_points.size());
  EXPECT_GT(spline_fit.gyro_bias_control_points.size(), 30u);
  ASSERT_TRUE(spline_fit.covariance_ok);
  EXPECT_GT(spline_fit.gyro_bias_std.minCoeff(), 0.0);
}

TEST(Fit, SaysWhenTheImuNeverRotates) {
  FitScenario scenario;
  scenario.trajectory = "translation_only";
  scenario.duration_s = 20.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise = scenario.noise;
  const FitResult result = Fit(data.imu, data.poses, options);
  bool said = false;
  for (const std::string& warning : result.warnings) {
    if (warning.find("singular") != std::string::npos ||
        warning.find("accel_bias is not determined") != std::string::npos) {
      said = true;
    }
  }
  EXPECT_TRUE(said) << ::testing::PrintToString(result.warnings);
}

TEST(Fit, KeepsPerSampleResidualsForTheReport) {
  FitScenario scenario;
  scenario.duration_s = 5.0;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.keep_samples = true;
  options.covariance.compute = false;
  const FitResult result = Fit(data.imu, data.poses, options);
  EXPECT_EQ(static_cast<int>(result.imu_samples.size()), result.num_imu_samples);
  EXPECT_EQ(static_cast<int>(result.pose_samples.size()), result.num_poses);
  EXPECT_EQ(result.imu_samples.front().t_ns, data.imu.front().t_ns);
  for (const FitImuSample& s : result.imu_samples) {
    EXPECT_LE((s.gyro_fitted - s.gyro_measured).norm(), 1e-7);
    EXPECT_LE((s.accel_fitted - s.accel_measured).norm(), 1e-6);
  }
}

// ---- Bad input: one clear message naming the likely cause ----

FitData SmallData() {
  FitScenario scenario;
  scenario.duration_s = 6.0;
  return MakeFitData(scenario);
}

std::string FitError(const std::vector<ImuSample>& imu,
                     const std::vector<StampedPose>& poses,
                     const FitOptions& options) {
  try {
    Fit(imu, poses, options);
  } catch (const Error& e) {
    return e.what();
  }
  return "(no error)";
}

TEST(FitErrors, TimeRangesThatDoNotOverlap) {
  FitData data = SmallData();
  for (StampedPose& p : data.poses) p.t_ns += 1'000'000'000'000;  // 1000 s later
  EXPECT_THAT(FitError(data.imu, data.poses, QuietOptions()),
              AllOf(HasSubstr("do not overlap"), HasSubstr("time bases")));
}

TEST(FitErrors, DataTooShortForTheKnotSpacing) {
  const FitData data = SmallData();
  FitOptions options = QuietOptions();
  options.model.knot_spacing_s = 2.0;
  EXPECT_THAT(FitError(data.imu, data.poses, options),
              AllOf(HasSubstr("too short for knot spacing 2 s"), HasSubstr("--knot-spacing")));
}

TEST(FitErrors, GyroInDegreesPerSecond) {
  FitData data = SmallData();
  for (ImuSample& s : data.imu) s.gyro *= kRadToDeg;
  EXPECT_THAT(FitError(data.imu, data.poses, QuietOptions()), HasSubstr("--gyro-unit deg/s"));
}

TEST(FitErrors, AccelerometerInUnitsOfG) {
  FitData data = SmallData();
  for (ImuSample& s : data.imu) s.accel /= 9.80665;
  EXPECT_THAT(FitError(data.imu, data.poses, QuietOptions()), HasSubstr("--accel-unit g"));
}

TEST(FitErrors, TimeOffsetBeyondTheSearchRange) {
  FitScenario scenario;
  scenario.duration_s = 10.0;
  scenario.pose_rate_hz = 20.0;
  scenario.time_offset_s = 0.3;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.estimate_time_offset = true;
  options.max_time_offset_s = 0.1;
  EXPECT_THAT(FitError(data.imu, data.poses, options),
              AllOf(HasSubstr("beyond the search range"), HasSubstr("--max-time-offset")));
}

TEST(FitErrors, SolverFailureNamesTheLikelyCauses) {
  // Real noise against densities 1000x too small: the best fit leaves residuals ~1000x the
  // assumed noise.
  FitScenario scenario;
  scenario.duration_s = 6.0;
  scenario.imu_noise = true;
  const FitData data = MakeFitData(scenario);
  FitOptions options = QuietOptions();
  options.model.noise.gyroscope_noise_density *= 1e-3;
  options.model.noise.accelerometer_noise_density *= 1e-3;
  EXPECT_THAT(FitError(data.imu, data.poses, options),
              AllOf(HasSubstr("does not explain the data"),
                    HasSubstr("likely causes"),
                    HasSubstr("noise densities")));
}

TEST(FitErrors, BadOptions) {
  const FitData data = SmallData();
  FitOptions options = QuietOptions();
  options.pose_sigma_m = 0.0;
  EXPECT_THAT(FitError(data.imu, data.poses, options), HasSubstr("pose sigma [m]"));
  options = QuietOptions();
  options.estimate_time_offset = true;
  options.time_offset_s = 0.5;
  EXPECT_THAT(FitError(data.imu, data.poses, options), HasSubstr("outside the search range"));
  options = QuietOptions();
  options.model.knot_spacing_s = 0.004;  // below two IMU periods at 200 Hz
  EXPECT_THAT(FitError(data.imu, data.poses, options), HasSubstr("below two IMU periods"));
}

// ---- Helpers ----

std::vector<ImuSample> SineGyro(double frequency_hz, double seconds) {
  std::vector<ImuSample> imu;
  for (int k = 0; k <= static_cast<int>(seconds * 200.0); ++k) {
    ImuSample s;
    s.t_ns = static_cast<int64_t>(k) * 5'000'000;
    const double t = k / 200.0;
    s.gyro = Eigen::Vector3d(std::sin(2.0 * kPi * frequency_hz * t), 0.0, 0.0);
    imu.push_back(s);
  }
  return imu;
}

TEST(ChooseKnotSpacing, FollowsTheBandwidthOfTheMotion) {
  ImuNoise noise;
  std::string rule;
  EXPECT_EQ(ChooseKnotSpacing(SineGyro(0.1, 60.0), noise, &rule), 0.2);
  EXPECT_THAT(rule, HasSubstr("automatic: 0.2 s"));
  // A 4 Hz rate: a 0.05 s average keeps sinc(0.2) = 0.94 of it (0.4% of the variance left).
  EXPECT_EQ(ChooseKnotSpacing(SineGyro(4.0, 20.0), noise, &rule), 0.05);
  // 10 Hz: 0.05 s would leave ~13% (sinc(0.5) = 0.64), 0.025 s about 1%.
  EXPECT_EQ(ChooseKnotSpacing(SineGyro(10.0, 20.0), noise, &rule), 0.025);
}

TEST(EstimateTimeOffsetByCorrelation, FindsAnInjectedOffsetDespiteBiasAndNoise) {
  FitScenario scenario;
  scenario.duration_s = 20.0;
  scenario.imu_noise = true;
  scenario.pose_noise = true;
  scenario.pose_rate_hz = 20.0;
  scenario.time_offset_s = 0.012;
  scenario.T_m_s = SE3d(SO3d::Exp(Eigen::Vector3d(0.5, -0.3, 1.0)), Eigen::Vector3d::Zero());
  const FitData data = MakeFitData(scenario);
  double offset = 0.0;
  bool at_edge = true;
  ASSERT_TRUE(EstimateTimeOffsetByCorrelation(data.imu, data.poses, 0.0, 0.1, &offset, &at_edge));
  EXPECT_FALSE(at_edge);
  // An initial guess for the solver: within half an IMU period (noise-free data gives it to
  // ~1e-5 s; here 1 mrad pose noise at 20 Hz is ~0.03 rad/s of rate noise per interval).
  EXPECT_NEAR(offset, 0.012, 2.5e-3);
}

}  // namespace
}  // namespace splinecal
