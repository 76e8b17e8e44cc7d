// `splinecal calibrate`: camera-IMU calibration in continuous time, rolling shutter included
// (calib/calibrate.h). Reads the IMU (EuRoC imu0/data.csv), the detected points
// (observations.csv), the camera rig (Kalibr camchain.yaml) and optionally the target; writes
// camchain-imucam.yaml (Kalibr's keys), result.yaml, report.html, spline.csv and
// reprojection_errors.csv. See docs/calibrate.md.
#include <gflags/gflags.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include "splinecal/calib/calibrate.h"
#include "splinecal/cli/command.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/kalibr_yaml.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/io/output_dir.h"
#include "splinecal/io/poses.h"
#include "splinecal/io/spline_csv.h"
#include "splinecal/io/target_yaml.h"
#include "splinecal/io/yaml_writer.h"
#include "splinecal/report/svg_plot.h"
#include "splinecal/string_printf.h"

DEFINE_string(observations,
              "",
              "Detected points, observations.csv: #t_ns,cam_id,point_id,u,v (frame stamp in the "
              "camera clock [ns], pixel [px]) [path]");
DEFINE_bool(rolling_shutter,
            false,
            "Estimate each camera's line_delay [s/row] (rolling shutter); without it the "
            "camchain's line_delay is kept (0: global shutter)");
DEFINE_bool(no_time_offset,
            false,
            "Keep the camchain's timeshift_cam_imu instead of estimating it");
DEFINE_double(pixel_sigma,
              0.0,
              "Pixel noise std [px] weighting the reprojection residuals; 0 estimates it from the "
              "residuals (robustly) and solves again");
DEFINE_double(huber, 2.0, "Huber threshold of the reprojection residuals [px]; 0 disables it");
DEFINE_int32(min_corners, 8, "Frames with fewer target corners are not used");
DEFINE_string(initial_poses,
              "",
              "Initial IMU trajectory T_w_s in the IMU clock, EuRoC ground-truth or TUM format "
              "(e.g. aligned_poses.csv of `splinecal align` on SLAM poses) [path]; needed without "
              "--target, optional with it");

namespace splinecal {
namespace cli {
namespace {

constexpr double kPi = 3.14159265358979323846;
// At most this many points per series in report.html (the file stays a few MB).
constexpr size_t kMaxPlotPoints = 6000;


// Every `stride`-th element so that at most kMaxPlotPoints remain.
size_t Stride(size_t n) { return std::max<size_t>(1, (n + kMaxPlotPoints - 1) / kMaxPlotPoints); }

void WriteCameraYaml(const CameraEstimate& c, YamlWriter* yaml) {
  yaml->Matrix("T_cam_imu", c.calibration.T_cam_imu.matrix());
  yaml->Vector("rotation_std_deg", c.rotation_std_deg);
  yaml->Vector("translation_std_m", c.translation_std_m);
  yaml->Scalar("timeshift_cam_imu", c.calibration.time_offset_s);
  yaml->Scalar("timeshift_estimated", c.time_offset_estimated);
  yaml->Scalar("timeshift_std_s", c.time_offset_std_s);
  yaml->Scalar("line_delay", c.calibration.line_delay_s);
  yaml->Scalar("line_delay_estimated", c.line_delay_estimated);
  yaml->Scalar("line_delay_std", c.line_delay_std_s);
  yaml->Scalar("reprojection_rms_px", c.reprojection_rms_px);
  yaml->Scalar("num_frames", c.num_frames);
  yaml->Scalar("num_observations", c.num_observations);
}

std::string ResultYaml(const CalibrationResult& r, const CalibrateOptions& options) {
  YamlWriter yaml;
  yaml.Comment(
      "splinecal calibrate: cam0's estimates at the top level (every camera under "
      "cameras); T_cam_imu maps IMU points into the camera; t_imu = t_cam + "
      "timeshift_cam_imu; row r is exposed at t_frame + r * line_delay; stds in the "
      "right tangent of T_cam_imu (rotation, IMU frame) and of t_cam_imu (camera frame)");
  WriteCameraYaml(r.cameras[0], &yaml);
  yaml.Vector("gyro_bias", r.gyro_bias);
  yaml.Vector("gyro_bias_std", r.gyro_bias_std);
  yaml.Vector("accel_bias", r.accel_bias);
  yaml.Vector("accel_bias_std", r.accel_bias_std);
  yaml.Vector("gravity_w", r.gravity_w);
  yaml.Scalar("reprojection_rms_px", r.reprojection_rms_px);
  yaml.Scalar("pixel_sigma_px", r.pixel_sigma_px);
  yaml.Scalar("pixel_sigma_estimated", r.pixel_sigma_estimated);
  yaml.Scalar("gyro_rms", r.gyro_rms);
  yaml.Scalar("accel_rms", r.accel_rms);
  yaml.Scalar("num_imu_samples", r.num_imu_samples);
  yaml.Scalar("num_landmarks", r.num_landmarks);
  yaml.Scalar("knot_spacing_s", 1e-9 * static_cast<double>(r.layout.dt_ns));
  yaml.Scalar("bias_model", options.model.bias_model == BiasModel::kSpline ? "spline" : "constant");
  yaml.Scalar("rolling_shutter", options.rolling_shutter);
  yaml.Scalar("huber_px", options.huber_px);
  yaml.Scalar("iterations", r.solve.iterations);
  yaml.Scalar("rounds", r.solve.rounds);
  yaml.Scalar("initialisation_time_s", r.initialisation_time_s);
  yaml.Scalar("solve_time_s", r.solve.solve_time_s);
  yaml.Scalar("covariance_time_s", r.covariance_time_s);
  yaml.Scalar("covariance_ok", r.covariance_ok);
  yaml.Scalar("termination", r.solve.termination);
  if (r.cameras.size() > 1) {
    yaml.BeginMap("cameras");
    for (size_t c = 0; c < r.cameras.size(); ++c) {
      yaml.BeginMap("cam" + std::to_string(c));
      WriteCameraYaml(r.cameras[c], &yaml);
      yaml.EndMap();
    }
    yaml.EndMap();
  }
  yaml.StringList("warnings", r.warnings);
  return yaml.str();
}

std::string ReprojectionCsv(const CalibrationResult& r) {
  std::ostringstream out;
  out << "#t_ns,cam_id,point_id,u,v,error_u,error_v\n";
  for (const ReprojectionSample& s : r.reprojection_samples) {
    out << s.t_ns << ',' << s.cam_id << ',' << s.point_id << ',' << FormatDouble(s.uv.x()) << ','
        << FormatDouble(s.uv.y()) << ',' << FormatDouble(s.error.x()) << ','
        << FormatDouble(s.error.y()) << '\n';
  }
  return out.str();
}

std::string ReportHtml(const CalibrationResult& r, const std::string& title) {
  const int64_t t0 = r.layout.t0_ns;
  auto seconds = [t0](int64_t t_ns) { return 1e-9 * static_cast<double>(t_ns - t0); };
  // Reprojection errors: scatter and over time.
  plot::Figure reprojection;
  reprojection.title = "Reprojection errors (predicted - observed)";
  reprojection.columns = 2;
  plot::Panel& scatter = reprojection.panels.emplace_back();
  scatter.title = "error scatter";
  scatter.x = {"u error [px]", plot::Scale::kLinear};
  scatter.y = {"v error [px]", plot::Scale::kLinear};
  scatter.equal_aspect = true;
  scatter.legend = plot::LegendPosition::kNone;
  plot::Panel& over_time = reprojection.panels.emplace_back();
  over_time.title = "error norm over time";
  over_time.x = {"time [s] (IMU spline)", plot::Scale::kLinear};
  over_time.y = {"|error| [px]", plot::Scale::kLinear};
  over_time.legend = plot::LegendPosition::kNone;
  plot::Series& points = scatter.series.emplace_back();
  points.line = false;
  points.marker = plot::Marker::kCircle;
  points.marker_size = 1.2;
  plot::Series& norms = over_time.series.emplace_back();
  norms.line = false;
  norms.marker = plot::Marker::kCircle;
  norms.marker_size = 1.2;
  const size_t stride = Stride(r.reprojection_samples.size());
  for (size_t k = 0; k < r.reprojection_samples.size(); k += stride) {
    const ReprojectionSample& s = r.reprojection_samples[k];
    points.x.push_back(s.error.x());
    points.y.push_back(s.error.y());
    norms.x.push_back(seconds(s.t_ns));
    norms.y.push_back(s.error.norm());
  }
  // IMU residuals.
  plot::Figure imu;
  imu.title = "IMU residuals (predicted - measured)";
  imu.columns = 1;
  imu.panel_width = 880.0;
  imu.panel_height = 260.0;
  const char* axes[3] = {"x", "y", "z"};
  for (int sensor = 0; sensor < 2; ++sensor) {
    plot::Panel& panel = imu.panels.emplace_back();
    panel.x = {"time [s] (IMU spline)", plot::Scale::kLinear};
    panel.y = {sensor == 0 ? "gyro residual [rad/s]" : "accel residual [m/s^2]",
               plot::Scale::kLinear};
    const size_t s_stride = Stride(r.imu_samples.size());
    for (int a = 0; a < 3; ++a) {
      plot::Series& series = panel.series.emplace_back();
      series.label = axes[a];
      series.line_width = 0.8;
      for (size_t k = 0; k < r.imu_samples.size(); k += s_stride) {
        const ImuResidualRecord& s = r.imu_samples[k];
        series.x.push_back(seconds(s.t_ns));
        series.y.push_back(sensor == 0 ? s.gyro_error[a] : s.accel_error[a]);
      }
    }
  }
  // Trajectory.
  plot::Figure trajectory;
  trajectory.title = "IMU trajectory in the target frame";
  trajectory.columns = 2;
  plot::Panel& top = trajectory.panels.emplace_back();
  top.title = "top view";
  top.x = {"x [m]", plot::Scale::kLinear};
  top.y = {"y [m]", plot::Scale::kLinear};
  top.equal_aspect = true;
  top.legend = plot::LegendPosition::kNone;
  plot::Panel& height = trajectory.panels.emplace_back();
  height.title = "position over time";
  height.x = {"time [s] (IMU spline)", plot::Scale::kLinear};
  height.y = {"position [m]", plot::Scale::kLinear};
  const SE3Splined spline = r.MakeSpline();
  plot::Series& xy = top.series.emplace_back();
  std::vector<plot::Series> components(3);
  for (int a = 0; a < 3; ++a) components[a].label = axes[a];
  const int64_t step = std::max<int64_t>(1, (spline.end_time_ns() - spline.start_time_ns()) / 3000);
  for (int64_t t = spline.start_time_ns(); t <= spline.end_time_ns(); t += step) {
    const Eigen::Vector3d p = spline.PoseNs(t).translation();
    xy.x.push_back(p.x());
    xy.y.push_back(p.y());
    for (int a = 0; a < 3; ++a) {
      components[a].x.push_back(seconds(t));
      components[a].y.push_back(p[a]);
    }
  }
  for (plot::Series& s : components) height.series.push_back(std::move(s));

  std::ostringstream html;
  html << "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>" << plot::EscapeXml(title)
       << "</title>\n<style>body{font-family:sans-serif;margin:2em;max-width:1000px}"
          "table{border-collapse:collapse}td,th{border:1px solid #ccc;padding:3px 8px;"
          "text-align:right}th{text-align:left}</style></head><body>\n";
  html << "<h1>" << plot::EscapeXml(title) << "</h1>\n<table>\n";
  for (size_t c = 0; c < r.cameras.size(); ++c) {
    const CameraEstimate& e = r.cameras[c];
    const Eigen::Vector3d rpy = e.calibration.T_cam_imu.so3().Log() * 180.0 / kPi;
    const Eigen::Vector3d t = e.calibration.T_cam_imu.translation();
    html << "<tr><th colspan=3>cam" << c << "</th></tr>\n";
    html << "<tr><th>T_cam_imu rotation vector [deg]</th><td>" << StringPrintf("%.4f", rpy.x())
         << ", " << StringPrintf("%.4f", rpy.y()) << ", " << StringPrintf("%.4f", rpy.z())
         << "</td><td>std " << StringPrintf("%.4f", e.rotation_std_deg.x()) << ", "
         << StringPrintf("%.4f", e.rotation_std_deg.y()) << ", "
         << StringPrintf("%.4f", e.rotation_std_deg.z()) << "</td></tr>\n";
    html << "<tr><th>T_cam_imu translation [mm]</th><td>" << StringPrintf("%.2f", 1e3 * t.x())
         << ", " << StringPrintf("%.2f", 1e3 * t.y()) << ", " << StringPrintf("%.2f", 1e3 * t.z())
         << "</td><td>std " << StringPrintf("%.2f", 1e3 * e.translation_std_m.x()) << ", "
         << StringPrintf("%.2f", 1e3 * e.translation_std_m.y()) << ", "
         << StringPrintf("%.2f", 1e3 * e.translation_std_m.z()) << "</td></tr>\n";
    html << "<tr><th>timeshift_cam_imu [ms]</th><td>"
         << StringPrintf("%.4f", 1e3 * e.calibration.time_offset_s) << "</td><td>std "
         << StringPrintf("%.4f", 1e3 * e.time_offset_std_s) << "</td></tr>\n";
    html << "<tr><th>line_delay [us/row]</th><td>"
         << StringPrintf("%.4f", 1e6 * e.calibration.line_delay_s) << "</td><td>std "
         << StringPrintf("%.4f", 1e6 * e.line_delay_std_s) << "</td></tr>\n";
    html << "<tr><th>reprojection RMS [px]</th><td>" << StringPrintf("%.3f", e.reprojection_rms_px)
         << "</td><td>" << e.num_observations << " points in " << e.num_frames
         << " frames</td></tr>\n";
  }
  html << "<tr><th>gyro bias [rad/s]</th><td colspan=2>" << StringPrintf("%.3e", r.gyro_bias.x())
       << ", " << StringPrintf("%.3e", r.gyro_bias.y()) << ", "
       << StringPrintf("%.3e", r.gyro_bias.z()) << "</td></tr>\n";
  html << "<tr><th>accel bias [m/s^2]</th><td colspan=2>" << StringPrintf("%.3e", r.accel_bias.x())
       << ", " << StringPrintf("%.3e", r.accel_bias.y()) << ", "
       << StringPrintf("%.3e", r.accel_bias.z()) << "</td></tr>\n";
  html << "<tr><th>IMU residual RMS</th><td colspan=2>gyro " << StringPrintf("%.3e", r.gyro_rms)
       << " rad/s, accel " << StringPrintf("%.3e", r.accel_rms) << " m/s^2</td></tr>\n";
  html << "<tr><th>pixel sigma [px]</th><td colspan=2>" << StringPrintf("%.3f", r.pixel_sigma_px)
       << (r.pixel_sigma_estimated ? " (estimated)" : " (given)") << "</td></tr>\n";
  html << "</table>\n";
  if (!r.warnings.empty()) {
    html << "<h2>Warnings</h2>\n<ul>\n";
    for (const std::string& w : r.warnings) html << "<li>" << plot::EscapeXml(w) << "</li>\n";
    html << "</ul>\n";
  }
  html << "<h2>Reprojection</h2>\n" << plot::RenderSvg(reprojection) << "\n";
  html << "<h2>IMU</h2>\n" << plot::RenderSvg(imu) << "\n";
  html << "<h2>Trajectory</h2>\n" << plot::RenderSvg(trajectory) << "\n";
  html << "</body></html>\n";
  return html.str();
}

// What calibrate reads and checks before the initial guess and the solve
// (Command::read_inputs); Calibrate() checks the rest (time ranges, motion) before it allocates.
struct CalibrateInputs {
  CalibrateOptions options;
  Camchain camchain;
  std::unique_ptr<CalibrationTarget> target;  // nullptr: landmarks only
  std::vector<Observation> observations;
  std::vector<ImuSample> imu;
  std::vector<StampedPose> initial_poses;  // empty without --initial-poses
};

// Every observation's camera must be in the camchain: a cam_id beyond it means the camchain of
// another rig or a column mix-up.
void CheckCameraIds(const std::vector<Observation>& observations,
                    const Camchain& camchain,
                    const std::string& observations_path,
                    const std::string& camchain_path) {
  for (const Observation& o : observations) {
    if (o.cam_id >= static_cast<int>(camchain.size())) {
      throw Error(observations_path,
                  0,
                  "cam_id " + std::to_string(o.cam_id) + " (frame t_ns " +
                      std::to_string(o.t_ns) + ") has no camera in " + camchain_path +
                      ", which describes " + std::to_string(camchain.size()) +
                      " camera(s): wrong camchain or cam_id column");
    }
  }
}

CalibrateInputs ReadCalibrateInputs() {
  const std::string& imu_path = RequiredFlag("imu", FLAGS_imu);
  const std::string& observations_path = RequiredFlag("observations", FLAGS_observations);
  const std::string& camchain_path = RequiredFlag("camchain", FLAGS_camchain);
  RequiredFlag("out", FLAGS_out);
  if (FLAGS_target.empty() && FLAGS_initial_poses.empty()) {
    throw Error(
        "without --target, --initial-poses is needed (the IMU trajectory, e.g. "
        "`splinecal align` on SLAM poses)");
  }
  CalibrateInputs in;
  CalibrateOptions& options = in.options;
  options.model.gravity_m_s2 = PositiveFlag("gravity", FLAGS_gravity);
  // 0: chosen from the IMU data (CalibrateOptions, estimation/knot_spacing.h).
  options.model.knot_spacing_s = KnotSpacingFlag(/*can_choose=*/true);
  options.rolling_shutter = FLAGS_rolling_shutter;
  options.estimate_time_offset = !FLAGS_no_time_offset;
  options.pixel_sigma_px = NonNegativeFlag("pixel-sigma", FLAGS_pixel_sigma);
  options.huber_px = NonNegativeFlag("huber", FLAGS_huber);
  if (FLAGS_min_corners < 4) throw Error("--min-corners: must be at least 4");
  options.min_corners_per_frame = FLAGS_min_corners;
  options.solver.num_threads = ThreadsFlag();
  options.solver.progress = [](const std::string& line) { Progress(line); };
  if (!FLAGS_imu_yaml.empty()) options.model.noise = ReadImuYaml(FLAGS_imu_yaml);

  in.camchain = ReadCamchainYaml(camchain_path);
  if (!FLAGS_target.empty()) {
    in.target = std::make_unique<CalibrationTarget>(ReadTargetYaml(FLAGS_target));
  }
  in.observations = ReadObservationsCsv(observations_path);
  CheckCameraIds(in.observations, in.camchain, observations_path, camchain_path);
  in.imu = ReadEurocImu(imu_path, ImuReadOptionsFromFlags());
  if (!FLAGS_initial_poses.empty()) in.initial_poses = ReadPoses(FLAGS_initial_poses);
  return in;
}

int RunCalibrate() {
  const CalibrateInputs in = ReadCalibrateInputs();
  const std::string& out_dir = FLAGS_out;
  const CalibrateOptions& options = in.options;
  const Camchain& camchain = in.camchain;
  const std::vector<Observation>& observations = in.observations;
  const std::vector<ImuSample>& imu = in.imu;
  OutputDir output(out_dir);
  if (FLAGS_imu_yaml.empty()) {
    Progress("calibrate: no --imu-yaml: weighting the IMU with the ADIS16448 (EuRoC) densities");
  }
  Progress("calibrate: " + std::to_string(observations.size()) + " observations, " +
           std::to_string(imu.size()) + " IMU samples, " + std::to_string(camchain.size()) +
           " camera(s)");
  std::vector<std::string> guess_warnings;
  std::unique_ptr<CalibrationInitialGuess> guess;
  CalibrationResult result;
  try {
    if (!in.initial_poses.empty()) {
      Progress("calibrate: initial guess from " + std::to_string(in.initial_poses.size()) +
               " initial poses");
      guess = std::make_unique<CalibrationInitialGuess>(InitialGuessFromImuPoses(
          imu, in.initial_poses, observations, camchain, options, &guess_warnings));
    }
    result = Calibrate(imu, observations, camchain, in.target.get(), options, guess.get());
  } catch (const Error& e) {
    // The library's messages start with "calibrate: "; the front end names the command already.
    const std::string prefix = "calibrate: ";
    if (e.path().empty() && e.message().rfind(prefix, 0) == 0) {
      throw Error(e.message().substr(prefix.size()));
    }
    throw;
  }
  result.warnings.insert(result.warnings.begin(), guess_warnings.begin(), guess_warnings.end());

  output.WriteFile("camchain-imucam.yaml", CamchainYamlText(result.camchain));
  output.WriteFile("result.yaml", ResultYaml(result, options));
  output.WriteFile("reprojection_errors.csv", ReprojectionCsv(result));
  std::ostringstream spline_csv;
  WriteSplineCsv(result.MakeSpline(), &spline_csv);
  output.WriteFile("spline.csv", spline_csv.str());
  output.WriteFile("report.html", ReportHtml(result, "splinecal calibrate"));
  output.Commit();

  for (size_t c = 0; c < result.cameras.size(); ++c) {
    const CameraEstimate& e = result.cameras[c];
    const Eigen::Matrix4d T = e.calibration.T_cam_imu.matrix();
    std::printf("cam%zu T_cam_imu:\n", c);
    for (int row = 0; row < 4; ++row) {
      std::printf("  [%12.9f %12.9f %12.9f %12.9f]\n", T(row, 0), T(row, 1), T(row, 2), T(row, 3));
    }
    std::printf("  rotation std [%.4f %.4f %.4f] deg, translation std [%.2f %.2f %.2f] mm\n",
                e.rotation_std_deg.x(),
                e.rotation_std_deg.y(),
                e.rotation_std_deg.z(),
                1e3 * e.translation_std_m.x(),
                1e3 * e.translation_std_m.y(),
                1e3 * e.translation_std_m.z());
    std::printf("  timeshift_cam_imu %.6f ms (std %.4f ms)%s\n",
                1e3 * e.calibration.time_offset_s,
                1e3 * e.time_offset_std_s,
                e.time_offset_estimated ? "" : " (fixed)");
    std::printf("  line_delay %.4f us/row (std %.4f us)%s\n",
                1e6 * e.calibration.line_delay_s,
                1e6 * e.line_delay_std_s,
                e.line_delay_estimated ? "" : " (fixed)");
    std::printf("  reprojection RMS %.3f px over %d points in %d frames\n",
                e.reprojection_rms_px,
                e.num_observations,
                e.num_frames);
  }
  std::printf("gyro RMS %.3e rad/s, accel RMS %.3e m/s^2, pixel sigma %.3f px%s\n",
              result.gyro_rms,
              result.accel_rms,
              result.pixel_sigma_px,
              result.pixel_sigma_estimated ? " (estimated)" : "");
  for (const std::string& w : result.warnings) std::printf("warning: %s\n", w.c_str());
  std::printf("wrote %s/camchain-imucam.yaml, result.yaml, report.html\n", out_dir.c_str());
  return 0;
}

}  // namespace

Command CalibrateCommand() {
  return {"calibrate",
          "camera-IMU calibration in continuous time: T_cam_imu, time offset, rolling-shutter "
          "line delay",
          "splinecal calibrate --imu FILE --observations FILE --camchain FILE [--target FILE]\n"
          "    [--initial-poses FILE] [--imu-yaml FILE] [--rolling-shutter] [--no-time-offset]\n"
          "    [--knot-spacing S] [--pixel-sigma PX] [--huber PX] [--min-corners N]\n"
          "    [--gravity M_S2] [--accel-unit m/s^2|g] [--gyro-unit rad/s|deg/s] [--threads N]\n"
          "    --out DIR",
          "Fits camera observations (a calibration target's corners and/or natural landmarks,\n"
          "one row per detected point in observations.csv) and IMU readings jointly on one\n"
          "SE(3) spline: estimates T_cam_imu, timeshift_cam_imu (t_imu = t_cam + shift) and,\n"
          "with --rolling-shutter, the line delay (row r exposed at t_frame + r * line_delay),\n"
          "plus the trajectory, IMU biases and gravity. The camchain's intrinsics are kept; its\n"
          "T_cam_imu, time offset and line delay are the starting point. The target gives the\n"
          "initial guess (PnP per frame, then the fit of `splinecal fit`); without a target,\n"
          "--initial-poses does (e.g. `splinecal align` on SLAM poses). Writes\n"
          "camchain-imucam.yaml (Kalibr's keys), result.yaml with standard deviations and\n"
          "warnings, report.html, spline.csv and reprojection_errors.csv. See docs/calibrate.md.",
          {{"imu", ""},
           {"observations", ""},
           {"camchain",
            "Camera rig, Kalibr camchain.yaml: intrinsics, distortion, resolution; "
            "T_cam_imu, timeshift_cam_imu, line_delay as the starting point [path]"},
           {"target",
            "Calibration target: Kalibr aprilgrid/checkerboard YAML or target_type: "
            "points [path]; point ids not in it are natural landmarks"},
           {"initial_poses", ""},
           {"imu_yaml",
            "IMU noise densities, Kalibr imu.yaml [path]; weights the IMU residuals "
            "(default: ADIS16448)"},
           {"rolling_shutter", ""},
           {"no_time_offset", ""},
           {"knot_spacing", "Spline knot spacing dt [s]; 0 chooses it from the IMU data", "0.05"},
           {"pixel_sigma", ""},
           {"huber", ""},
           {"min_corners", ""},
           {"gravity", ""},
           {"accel_unit", ""},
           {"gyro_unit", ""},
           {"threads", ""},
           {"out", ""}},
          &RunCalibrate,
          [] { ReadCalibrateInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
