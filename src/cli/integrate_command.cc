// `splinecal integrate`: IMU dead reckoning with Euler, midpoint and RK4 steps (imu/integrate.h)
// from the ground-truth state at the start, and each method's drift against the ground truth
// (the seed's Euler-versus-midpoint experiment). Writes result.yaml, trajectory_<method>.csv
// (EuRoC ground-truth format) and trajectory.svg (top view) to --out. See docs/integrate.md.
#include <gflags/gflags.h>

#include <cstdio>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/report/integrate_report.h"

DEFINE_string(groundtruth,
              "",
              "Ground truth, EuRoC state_groundtruth_estimate0/data.csv (t_ns, p, q wxyz, v, "
              "gyro bias, accel bias) [path]");
DEFINE_string(method,
              "euler,midpoint,rk4",
              "Integration methods, comma-separated: euler, "
              "midpoint, rk4");
DEFINE_double(start,
              0.0,
              "Start [s] after the first IMU sample; the integration starts at the "
              "first ground-truth row at or after it");

namespace splinecal {
namespace cli {
namespace {

// What integrate reads and checks before integrating anything (Command::read_inputs).
struct IntegrateInputs {
  std::string out_dir;
  std::vector<IntegrationMethod> methods;
  double gravity = 0.0;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
  IntegrationSpan span;
};

IntegrateInputs ReadIntegrateInputs() {
  IntegrateInputs in;
  const std::string imu_path = ImuInputName();
  const std::string& truth_path = RequiredFlag("groundtruth", FLAGS_groundtruth);
  in.out_dir = RequiredFlag("out", FLAGS_out);
  in.methods = ParseIntegrationMethods(FLAGS_method);
  in.gravity = PositiveFlag("gravity", FLAGS_gravity);
  SpanFlagNs("start", FLAGS_start, /*allow_zero=*/true);
  SpanFlagNs("duration", FLAGS_duration, /*allow_zero=*/true);
  in.imu = ReadImuFlags();
  in.truth = ReadEurocGroundTruth(truth_path);
  in.span =
      ChooseIntegrationSpan(in.imu, in.truth, FLAGS_start, FLAGS_duration, imu_path, truth_path);
  return in;
}

int RunIntegrate() {
  const IntegrateInputs in = ReadIntegrateInputs();
  const std::string& out_dir = in.out_dir;
  OutputDir output(out_dir);
  const int64_t start_ns = in.truth[in.span.start_row].t_ns;
  Progress("integrate: " + std::to_string((in.span.end_ns - start_ns) * 1e-9) +
           " s from t = " + std::to_string(start_ns) + " ns");
  const IntegrationRun run = RunIntegration(in.imu, in.truth, in.span, in.methods, in.gravity);

  std::printf("%-9s %22s %24s %12s\n",
              "method",
              "final_position_error_m",
              "final_rotation_error_deg",
              "ate_rmse_m");
  for (const IntegrationRun::Method& m : run.methods) {
    std::printf("%-9s %22.6g %24.6g %12.6g\n",
                IntegrationMethodName(m.method),
                m.drift.final_position_error_m,
                m.drift.final_rotation_error_deg,
                m.drift.ate_rmse_m);
  }
  output.WriteFiles(run.files);
  output.Commit();
  std::printf("wrote %s/result.yaml, trajectory_<method>.csv, trajectory.svg\n", out_dir.c_str());
  return 0;
}

}  // namespace

Command IntegrateCommand() {
  return {"integrate",
          "IMU dead reckoning (euler, midpoint, rk4) and its drift against ground truth",
          "splinecal integrate (--imu FILE\n"
          "    | --bag FILE [--imu-topic T] [--bag-time header|receive])\n"
          "    --groundtruth FILE [--method euler,midpoint,rk4]\n"
          "    [--start S] [--duration S] [--gravity M_S2] [--accel-unit m/s^2|g]\n"
          "    [--gyro-unit rad/s|deg/s] --out DIR",
          "Integrates the IMU readings from the ground-truth state (position, orientation,\n"
          "world velocity) and biases of the first ground-truth row at or after --start, with\n"
          "each --method: euler, midpoint (the seed's two) and rk4 (exact SO(3) exponential for\n"
          "the orientation in all three). Errors are taken at the ground-truth times, the\n"
          "integrated trajectory interpolated there, without alignment. Writes result.yaml\n"
          "(final_position_error_m, final_rotation_error_deg, ate_rmse_m per method),\n"
          "trajectory_<method>.csv (EuRoC ground-truth format at the IMU times) and\n"
          "trajectory.svg (top view of the ground truth and each method). Prints the drift\n"
          "table. See docs/integrate.md.",
          WithFlags(ImuInputFlags(),
                    {{"groundtruth", ""},
                     {"method", ""},
                     {"start", ""},
                     {"duration", "Duration [s] from the start; 0: until the end of the data",
                      "0"},
                     {"gravity", ""},
                     {"accel_unit", ""},
                     {"gyro_unit", ""},
                     {"out", ""}}),
          &RunIntegrate,
          [] { ReadIntegrateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
