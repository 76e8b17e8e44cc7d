#include "splinecal/report/integrate_report.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "splinecal/error.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/plot/plot_decimation.h"
#include "splinecal/plot/svg_plot.h"

namespace splinecal {

namespace {

// At most this many points per method in trajectory.svg.
constexpr int kMaxPlotPoints = 4000;

}  // namespace

IntegrationSpan ChooseIntegrationSpan(const std::vector<ImuSample>& imu,
                                      const std::vector<GroundTruthState>& truth,
                                      double start_s,
                                      double duration_s,
                                      const std::string& imu_path,
                                      const std::string& truth_path) {
  const int64_t start_ns = std::llround(start_s * 1e9);
  const int64_t duration_ns = std::llround(duration_s * 1e9);
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
  IntegrationSpan span;
  span.start_row = static_cast<size_t>(row - truth.begin());
  span.end_ns = data_end_ns;
  if (duration_s > 0.0) {  // 0: until the end of the data
    span.end_ns = row->t_ns + duration_ns;
    if (span.end_ns > data_end_ns) {
      throw Error(imu_path,
                  0,
                  "--duration " + std::to_string(duration_s) +
                      " s from the start reaches past "
                      "the end of the IMU or ground-truth data (" +
                      std::to_string((data_end_ns - row->t_ns) * 1e-9) + " s available)");
    }
  }
  return span;
}

IntegrationRun RunIntegration(const std::vector<ImuSample>& imu,
                              const std::vector<GroundTruthState>& truth,
                              const IntegrationSpan& span,
                              const std::vector<IntegrationMethod>& methods,
                              double gravity_m_s2) {
  const int64_t end_ns = span.end_ns;
  const auto row = truth.begin() + static_cast<std::ptrdiff_t>(span.start_row);
  IntegrationRun run;
  run.start = NavStateFromGroundTruth(*row);
  const NavState& start = run.start;
  const ImuBias bias = BiasFromGroundTruth(*row);
  const Eigen::Vector3d g_w(0.0, 0.0, -gravity_m_s2);

  YamlWriter yaml;
  yaml.Comment(
      "splinecal integrate: dead reckoning from the ground-truth state at start_t_ns; "
      "errors against the ground truth at its own times (docs/integrate.md)");
  yaml.Scalar("start_t_ns", start.t_ns);
  yaml.Scalar("end_t_ns", end_ns);
  yaml.Scalar("duration_s", (end_ns - start.t_ns) * 1e-9);
  yaml.Scalar("gravity_m_s2", gravity_m_s2);
  yaml.Vector("gyro_bias", bias.gyro);
  yaml.Vector("accel_bias", bias.accel);

  plot::Figure figure;
  figure.title = "IMU dead reckoning, top view";
  figure.panel_width = 560.0;
  figure.panel_height = 480.0;
  plot::Panel& panel = plot::AddPanel(&figure, "", "x [m]", "y [m]");
  panel.equal_aspect = true;
  plot::Series& truth_series = panel.series.emplace_back();
  truth_series.label = "ground truth";
  truth_series.color = "#000000";
  truth_series.line_width = 2.0;
  for (auto it = row; it != truth.end() && it->t_ns <= end_ns; ++it) {
    truth_series.x.push_back(it->p_w_s.x());
    truth_series.y.push_back(it->p_w_s.y());
  }

  for (IntegrationMethod method : methods) {
    const std::string name = IntegrationMethodName(method);
    std::vector<NavState> trajectory;
    IntegrateImu(imu, start, end_ns, bias, g_w, method, &trajectory);
    const DriftMetrics drift = ComputeDrift(trajectory, truth);
    run.methods.push_back({method, drift});
    yaml.BeginMap(name);
    yaml.Scalar("final_position_error_m", drift.final_position_error_m);
    yaml.Scalar("final_rotation_error_deg", drift.final_rotation_error_deg);
    yaml.Scalar("ate_rmse_m", drift.ate_rmse_m);
    yaml.Scalar("num_compared", drift.num_compared);
    yaml.Scalar("final_t_ns", drift.final_t_ns);
    yaml.EndMap();

    std::vector<GroundTruthState> rows;
    rows.reserve(trajectory.size());
    for (const NavState& state : trajectory) rows.push_back(ToGroundTruthState(state, bias));
    std::ostringstream csv;
    WriteEurocGroundTruth(rows, &csv);
    run.files.push_back({"trajectory_" + name + ".csv", csv.str()});

    plot::Series& series = panel.series.emplace_back();
    series.label = name;
    series.dashed = method == IntegrationMethod::kRk4;
    for (size_t k : plot::DecimatedIndices(trajectory.size(), kMaxPlotPoints, /*keep_last=*/true)) {
      series.x.push_back(trajectory[k].p_w_s.x());
      series.y.push_back(trajectory[k].p_w_s.y());
    }
  }
  run.files.push_back({"result.yaml", yaml.str()});
  run.files.push_back({"trajectory.svg", plot::RenderSvg(figure)});
  return run;
}

}  // namespace splinecal
