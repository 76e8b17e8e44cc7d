// `splinecal integrate`: IMU dead reckoning with Euler, midpoint and RK4 steps (imu/integrate.h)
// from the ground-truth state at the start, and each method's drift against the ground truth
// (the seed's Euler-versus-midpoint experiment). Writes result.yaml, trajectory_<method>.csv
// (EuRoC ground-truth format) and trajectory.svg (top view) to --out. See docs/integrate.md.
#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/imu/integrate.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/plot_decimation.h"
#include "splinecal/plot/svg_plot.h"

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

// At most this many points per method in trajectory.svg.
constexpr int kMaxPlotPoints = 4000;

// What integrate reads and checks before integrating anything (Command::read_inputs).
struct IntegrateInputs {
  std::string out_dir;
  std::vector<IntegrationMethod> methods;
  double gravity = 0.0;
  std::vector<ImuSample> imu;
  std::vector<GroundTruthState> truth;
  size_t start_row = 0;  // the ground-truth row the integration starts from
  int64_t end_ns = 0;
};

IntegrateInputs ReadIntegrateInputs() {
  IntegrateInputs in;
  const std::string& imu_path = RequiredFlag("imu", FLAGS_imu);
  const std::string& truth_path = RequiredFlag("groundtruth", FLAGS_groundtruth);
  in.out_dir = RequiredFlag("out", FLAGS_out);
  in.methods = ParseIntegrationMethods(FLAGS_method);
  in.gravity = PositiveFlag("gravity", FLAGS_gravity);
  const double start_s = FLAGS_start;
  const int64_t start_ns = SpanFlagNs("start", start_s, /*allow_zero=*/true);
  const double duration_s = FLAGS_duration;
  const int64_t duration_ns = SpanFlagNs("duration", duration_s, /*allow_zero=*/true);
  const bool duration_given = duration_s > 0.0;  // 0: until the end of the data

  in.imu = ReadEurocImu(imu_path, ImuReadOptionsFromFlags());
  in.truth = ReadEurocGroundTruth(truth_path);
  const std::vector<ImuSample>& imu = in.imu;
  const std::vector<GroundTruthState>& truth = in.truth;
  const int64_t data_end_ns = std::min(imu.back().t_ns, truth.back().t_ns);

  // The start: the first ground-truth row at or after first IMU time + start, inside the IMU.
  const int64_t wanted_ns = imu.front().t_ns + start_ns;
  auto row = std::lower_bound(truth.begin(),
                              truth.end(),
                              std::max(wanted_ns, imu.front().t_ns),
                              [](const GroundTruthState& s, int64_t t) { return s.t_ns < t; });
  if (row == truth.end() || row->t_ns >= data_end_ns) {
    throw Error(truth_path,
                0,
                "--start " + std::to_string(start_s) +
                    " s is outside the data: no ground-truth row between the IMU's first sample + "
                    "start and the end of the data (" +
                    std::to_string((data_end_ns - imu.front().t_ns) * 1e-9) +
                    " s after the first IMU sample)");
  }
  in.start_row = static_cast<size_t>(row - truth.begin());
  in.end_ns = data_end_ns;
  if (duration_given) {
    in.end_ns = row->t_ns + duration_ns;
    if (in.end_ns > data_end_ns) {
      throw Error(imu_path,
                  0,
                  "--duration " + std::to_string(duration_s) +
                      " s from the start reaches past "
                      "the end of the IMU or ground-truth data (" +
                      std::to_string((data_end_ns - row->t_ns) * 1e-9) + " s available)");
    }
  }
  return in;
}

int RunIntegrate() {
  const IntegrateInputs in = ReadIntegrateInputs();
  const std::string& out_dir = in.out_dir;
  const std::vector<ImuSample>& imu = in.imu;
  const std::vector<GroundTruthState>& truth = in.truth;
  const double gravity = in.gravity;
  const int64_t end_ns = in.end_ns;
  const auto row = truth.begin() + static_cast<std::ptrdiff_t>(in.start_row);
  const NavState start = NavStateFromGroundTruth(*row);
  const ImuBias bias = BiasFromGroundTruth(*row);
  const Eigen::Vector3d g_w(0.0, 0.0, -gravity);
  Progress("integrate: " + std::to_string((end_ns - start.t_ns) * 1e-9) +
           " s from t = " + std::to_string(start.t_ns) + " ns");

  OutputDir output(out_dir);
  YamlWriter yaml;
  yaml.Comment(
      "splinecal integrate: dead reckoning from the ground-truth state at start_t_ns; "
      "errors against the ground truth at its own times (docs/integrate.md)");
  yaml.Scalar("start_t_ns", start.t_ns);
  yaml.Scalar("end_t_ns", end_ns);
  yaml.Scalar("duration_s", (end_ns - start.t_ns) * 1e-9);
  yaml.Scalar("gravity_m_s2", gravity);
  yaml.Vector("gyro_bias", bias.gyro);
  yaml.Vector("accel_bias", bias.accel);

  plot::Figure figure;
  figure.title = "IMU dead reckoning, top view";
  figure.panel_width = 560.0;
  figure.panel_height = 480.0;
  plot::Panel& panel = figure.panels.emplace_back();
  panel.x = {"x [m]", plot::Scale::kLinear};
  panel.y = {"y [m]", plot::Scale::kLinear};
  panel.equal_aspect = true;
  plot::Series& truth_series = panel.series.emplace_back();
  truth_series.label = "ground truth";
  truth_series.color = "#000000";
  truth_series.line_width = 2.0;
  for (auto it = row; it != truth.end() && it->t_ns <= end_ns; ++it) {
    truth_series.x.push_back(it->p_w_s.x());
    truth_series.y.push_back(it->p_w_s.y());
  }

  std::printf("%-9s %22s %24s %12s\n",
              "method",
              "final_position_error_m",
              "final_rotation_error_deg",
              "ate_rmse_m");
  for (IntegrationMethod method : in.methods) {
    const std::string name = IntegrationMethodName(method);
    std::vector<NavState> trajectory;
    IntegrateImu(imu, start, end_ns, bias, g_w, method, &trajectory);
    const DriftMetrics drift = ComputeDrift(trajectory, truth);
    yaml.BeginMap(name);
    yaml.Scalar("final_position_error_m", drift.final_position_error_m);
    yaml.Scalar("final_rotation_error_deg", drift.final_rotation_error_deg);
    yaml.Scalar("ate_rmse_m", drift.ate_rmse_m);
    yaml.Scalar("num_compared", drift.num_compared);
    yaml.Scalar("final_t_ns", drift.final_t_ns);
    yaml.EndMap();
    std::printf("%-9s %22.6g %24.6g %12.6g\n",
                name.c_str(),
                drift.final_position_error_m,
                drift.final_rotation_error_deg,
                drift.ate_rmse_m);

    std::vector<GroundTruthState> rows;
    rows.reserve(trajectory.size());
    for (const NavState& state : trajectory) rows.push_back(ToGroundTruthState(state, bias));
    std::ostringstream csv;
    WriteEurocGroundTruth(rows, &csv);
    output.WriteFile("trajectory_" + name + ".csv", csv.str());

    plot::Series& series = panel.series.emplace_back();
    series.label = name;
    series.dashed = method == IntegrationMethod::kRk4;
    for (size_t k : plot::DecimatedIndices(trajectory.size(), kMaxPlotPoints, /*keep_last=*/true)) {
      series.x.push_back(trajectory[k].p_w_s.x());
      series.y.push_back(trajectory[k].p_w_s.y());
    }
  }
  output.WriteFile("result.yaml", yaml.str());
  output.WriteFile("trajectory.svg", plot::RenderSvg(figure));
  output.Commit();
  std::printf("wrote %s/result.yaml, trajectory_<method>.csv, trajectory.svg\n", out_dir.c_str());
  return 0;
}

}  // namespace

Command IntegrateCommand() {
  return {"integrate",
          "IMU dead reckoning (euler, midpoint, rk4) and its drift against ground truth",
          "splinecal integrate --imu FILE --groundtruth FILE [--method euler,midpoint,rk4]\n"
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
          {{"imu", ""},
           {"groundtruth", ""},
           {"method", ""},
           {"start", ""},
           {"duration", "Duration [s] from the start; 0: until the end of the data", "0"},
           {"gravity", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"out", ""}},
          &RunIntegrate,
          [] { ReadIntegrateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
