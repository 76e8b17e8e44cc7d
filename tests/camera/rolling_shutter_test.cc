#include "splinecal/camera/rolling_shutter.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "calib/camera_test_scene.h"
#include "splinecal/estimation/reprojection_cost.h"
#include "splinecal/lie/se3_manifold.h"

namespace splinecal {
namespace {

// The bound for the time solve against bisection [s] (docs/calibrate.md, "Tests"): 1e-9 s.
constexpr double kTimeTolerance = 1e-9;

// The row function of a world point seen from the test scene's spline at t_base + tau.
struct SplineRow {
  const SE3Splined* spline;
  const Camera* camera;
  SE3d T_c_s;
  double t_base_s;
  Eigen::Vector3d p_w;

  bool operator()(double tau, double* v, double* v_dot) const {
    const Segment<double> segment = spline->SegmentAt(t_base_s + tau);
    const internal::BodyState state =
        internal::EvaluateBodyState(spline->model(), spline->Knots(segment), segment);
    internal::PointProjection projection;
    if (!internal::ProjectPoint(*camera, T_c_s, state, p_w, 1.0, false, &projection)) {
      return false;
    }
    *v = projection.uv.y();
    *v_dot = projection.uv_dot.y();
    return true;
  }
};

// Bisection on F(tau) = tau - line_delay v(tau), increasing for D > 0, over the readout.
double Bisect(const SplineRow& row, double line_delay, int height) {
  double lo = 0.0;
  double hi = line_delay * (height - 1);
  auto F = [&](double tau) {
    double v = 0.0, v_dot = 0.0;
    CHECK(row(tau, &v, &v_dot));
    return tau - line_delay * v;
  };
  if (F(lo) >= 0.0) return lo;
  if (F(hi) <= 0.0) return hi;
  for (int i = 0; i < 200 && hi - lo > 1e-16; ++i) {
    const double mid = 0.5 * (lo + hi);
    (F(mid) < 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

TEST(SolveExposureTime, MatchesBisectionOnASpline) {
  const testing::CameraTestScene scene;
  const SE3Splined spline = scene.Spline();
  const SE3d T_c_s = PoseFromBlock(scene.T_c_s.data());
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  int solved = 0;
  int max_iterations = 0;
  for (int trial = 0; trial < 200; ++trial) {
    // A point seen at a random pixel and depth at a random time; then solved at a frame stamp a
    // little earlier, so the exposure is somewhere in the readout.
    const double line_delay = 1e-5 + 6e-5 * uniform(rng);  // 10..70 us per row
    const double t_frame = 0.2 + 0.6 * uniform(rng);
    const SE3d T_w_c = spline.Pose(t_frame) * T_c_s.inverse();
    Eigen::Vector3d ray;
    ASSERT_TRUE(scene.camera.Unproject(
        Eigen::Vector2d(50 + 650 * uniform(rng), 20 + 440 * uniform(rng)), &ray));
    const Eigen::Vector3d p_w = T_w_c * (ray * (0.5 + 2.0 * uniform(rng)));
    const SplineRow row{&spline, &scene.camera, T_c_s, t_frame, p_w};
    ExposureSolution solution;
    const double observed_row = 240.0;  // a deliberately poor start
    ASSERT_TRUE(SolveExposureTime(
        row, line_delay, scene.camera.height, line_delay * observed_row, &solution));
    const double reference = Bisect(row, line_delay, scene.camera.height);
    EXPECT_NEAR(solution.tau_s, reference, kTimeTolerance) << "trial " << trial;
    if (!solution.at_lower_bound && !solution.at_upper_bound) {
      // Within the tolerance (1e-12 s) of the root, measured in F = tau - ld v(tau).
      EXPECT_NEAR(solution.tau_s, line_delay * solution.row, 1e-12);
      ++solved;
    }
    max_iterations = std::max(max_iterations, solution.iterations);
  }
  EXPECT_GT(solved, 150);        // most points fall inside the readout
  EXPECT_LE(max_iterations, 6);  // quadratic convergence from a poor start
}

TEST(SolveExposureTime, GlobalShutterIsExactlyTheStamp) {
  const testing::CameraTestScene scene;
  const SE3Splined spline = scene.Spline();
  const SplineRow row{&spline,
                      &scene.camera,
                      PoseFromBlock(scene.T_c_s.data()),
                      0.5,
                      Eigen::Vector3d(0.0, 0.0, 0.0)};
  ExposureSolution solution;
  ASSERT_TRUE(SolveExposureTime(row, 0.0, scene.camera.height, 1.0, &solution));
  EXPECT_EQ(solution.tau_s, 0.0);
  EXPECT_EQ(solution.derivative, 1.0);
  const Eigen::Vector2d uv_dot(3.0, -4.0);
  EXPECT_EQ(RollingShutterCorrection(solution, 0.0, uv_dot), Eigen::Matrix2d::Identity());
  // d uv / d line_delay at 0 is the first-order effect of starting to read out: uv_dot * row.
  EXPECT_EQ(RollingShutterLineDelayJacobian(solution, scene.camera.height, uv_dot),
            uv_dot * solution.row);
}

TEST(SolveExposureTime, ClampsToTheReadout) {
  // A linear row function: v(tau) = v0 + rate * tau.
  const double line_delay = 2e-5;
  const int height = 480;
  auto linear = [](double v0, double rate) {
    return [v0, rate](double tau, double* v, double* v_dot) {
      *v = v0 + rate * tau;
      *v_dot = rate;
      return true;
    };
  };
  ExposureSolution above;
  ASSERT_TRUE(SolveExposureTime(linear(-30.0, 100.0), line_delay, height, 0.0, &above));
  EXPECT_EQ(above.tau_s, 0.0);
  EXPECT_TRUE(above.at_lower_bound);
  EXPECT_EQ(RollingShutterLineDelayJacobian(above, height, Eigen::Vector2d(1, 1)),
            Eigen::Vector2d::Zero());
  ExposureSolution below;
  ASSERT_TRUE(SolveExposureTime(linear(600.0, 100.0), line_delay, height, 0.0, &below));
  EXPECT_EQ(below.tau_s, line_delay * (height - 1));
  EXPECT_TRUE(below.at_upper_bound);
  EXPECT_EQ(RollingShutterLineDelayJacobian(below, height, Eigen::Vector2d(1, 0)),
            Eigen::Vector2d(height - 1.0, 0.0));
  ExposureSolution inside;
  ASSERT_TRUE(SolveExposureTime(linear(100.0, 2000.0), line_delay, height, 0.0, &inside));
  // tau = ld (v0 + rate tau)  =>  tau = ld v0 / (1 - ld rate).
  EXPECT_NEAR(inside.tau_s, line_delay * 100.0 / (1.0 - line_delay * 2000.0), 1e-17);
  EXPECT_FALSE(inside.at_lower_bound || inside.at_upper_bound);
}

TEST(SolveExposureTime, RefusesAPointFasterThanTheShutter) {
  // D = 1 - ld * rate <= 0: the point crosses rows faster than the shutter sweeps.
  auto fast = [](double tau, double* v, double* v_dot) {
    *v = 100.0 + 1e5 * tau;
    *v_dot = 1e5;
    return true;
  };
  ExposureSolution solution;
  EXPECT_FALSE(SolveExposureTime(fast, 2e-5, 480, 0.0, &solution));
}

}  // namespace
}  // namespace splinecal
