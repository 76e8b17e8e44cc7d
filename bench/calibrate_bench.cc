// `splinecal calibrate` on simulated rolling-shutter sequences: the target is a 60 s
// calibration (20 Hz camera -> 1200 frames, an aprilgrid with ~100 visible corners, 200 Hz IMU
// with the ADIS16448 noise) in at most 30 s on 2 cores. Reports the wall time of the whole
// Calibrate call (initial guess, solver rounds, covariance) and its parts as counters, for
// sequence lengths 15, 30 and 60 s (docs/calibrate.md, "Speed"). The sequence is simulated
// once per length, outside the timed region.
//
//   calibrate_bench --benchmark_filter=Calibrate/60
#include <benchmark/benchmark.h>

#include <cstdio>
#include <cstdlib>
#include <map>
#include <memory>

#include "splinecal/calib/calibrate.h"
#include "splinecal/calib/simulate_camera.h"

namespace splinecal {
namespace {

PinholeCamera EurocCamera() {
  PinholeCamera c;
  c.fu = 458.654;
  c.fv = 457.296;
  c.pu = 367.215;
  c.pv = 248.375;
  c.distortion = DistortionModel::kRadTan;
  c.distortion_coeffs << -0.28340811, 0.07395907, 0.00019359, 1.76187114e-05;
  c.width = 752;
  c.height = 480;
  return c;
}

struct Sequence {
  Camchain truth;
  Camchain start;
  CalibrationTarget target = MakeAprilGrid(6, 6, 0.088, 0.3);
  CalibrationSequence data;
};

const Sequence& GetSequence(int seconds) {
  static std::map<int, std::unique_ptr<Sequence>> cache;
  std::unique_ptr<Sequence>& s = cache[seconds];
  if (s) return *s;
  s = std::make_unique<Sequence>();
  CameraCalibration cam;
  cam.camera = EurocCamera();
  cam.T_cam_imu =
      SE3d(SO3d::Exp(Eigen::Vector3d(0.02, -0.01, 1.55)), Eigen::Vector3d(0.06, -0.02, 0.01));
  cam.timeshift_cam_imu_s = 0.0042;
  cam.line_delay_s = 3e-5;
  s->truth = {cam};
  cam.T_cam_imu =
      cam.T_cam_imu * SE3d::Exp((Vector6d() << 0.02, -0.015, 0.01, 0.03, -0.035, 0.02).finished());
  cam.timeshift_cam_imu_s = 0.0;
  cam.line_delay_s = 0.0;
  s->start = {cam};
  CalibrationSequenceOptions options;
  options.duration_s = seconds;
  options.imu.noise = ImuNoise::Adis16448();
  options.imu.gyro_bias = Eigen::Vector3d(0.002, -0.001, 0.0015);
  options.imu.accel_bias = Eigen::Vector3d(0.05, -0.03, 0.02);
  options.imu.seed = 1;
  options.camera.pixel_noise_px = 0.5;
  options.camera.seed = 101;
  options.camera.has_target = true;
  options.camera.target = s->target;
  s->data = SimulateCalibrationSequence(s->truth, options);
  return *s;
}

void BM_Calibrate(benchmark::State& state) {
  const Sequence& s = GetSequence(static_cast<int>(state.range(0)));
  CalibrateOptions options;
  options.rolling_shutter = true;
  options.num_threads = static_cast<int>(state.range(1));
  options.keep_residuals = false;
  CalibrationResult result;
  for (auto _ : state) {
    result = Calibrate(s.data.imu, s.data.cameras.observations, s.start, &s.target, options);
  }
  state.counters["frames"] = s.data.cameras.num_frames;
  state.counters["corners"] = s.data.cameras.num_target_observations;
  state.counters["iterations"] = result.iterations;
  state.counters["rounds"] = result.rounds;
  state.counters["init_s"] = result.initialisation_time_s;
  state.counters["solve_s"] = result.solve_time_s;
  state.counters["covariance_s"] = result.covariance_time_s;
  state.counters["rms_px"] = result.reprojection_rms_px;
  if (std::getenv("CALIBRATE_BENCH_REPORT") != nullptr)
    std::fprintf(stderr, "%s\n", result.solver_report.c_str());
}
BENCHMARK(BM_Calibrate)
    ->ArgNames({"seconds", "threads"})
    ->Args({15, 2})
    ->Args({30, 2})
    ->Args({60, 2})
    ->Args({60, 1})
    ->Unit(benchmark::kSecond)
    ->Iterations(1)
    ->UseRealTime();

}  // namespace
}  // namespace splinecal

BENCHMARK_MAIN();
