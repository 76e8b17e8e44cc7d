#include "splinecal/report/report_inputs.h"

#include <string>
#include <vector>

#include "splinecal/plot/svg_plot.h"
#include "splinecal/string_printf.h"

namespace splinecal {

std::string InputFilesHtml(const std::vector<ReportInput>& inputs) {
  std::string lines;
  for (const auto& [label, path] : inputs) {
    if (path.empty()) continue;
    if (!lines.empty()) lines += "<br>";
    lines += plot::EscapeXml(label) + ": " + plot::EscapeXml(path);
  }
  return lines.empty() ? std::string() : "<p>" + lines + "</p>\n";
}

std::string NoiseSourceText(const std::string& imu_yaml_path) {
  return imu_yaml_path.empty() ? "ADIS16448 defaults (EuRoC), no --imu-yaml given" : imu_yaml_path;
}

namespace {

struct DensityRow {
  ImuResidualKind kind;
  const char* unit;
};
constexpr DensityRow kDensityRows[] = {
    {ImuResidualKind::kGyro, "rad/s/sqrt(Hz)"},
    {ImuResidualKind::kGyroRandomWalk, "rad/s^2/sqrt(Hz)"},
    {ImuResidualKind::kAccel, "m/s^2/sqrt(Hz)"},
    {ImuResidualKind::kAccelRandomWalk, "m/s^3/sqrt(Hz)"},
};

// Why a density was (not) re-estimated, in words.
std::string DensityNote(const ImuNoiseEstimate& noise, ImuResidualKind kind) {
  const int k = static_cast<int>(kind);
  if (noise.mode == ImuNoiseMode::kGiven) return "given (--imu-noise given)";
  if (noise.num_residuals[k] == 0) return "no such residuals (constant bias)";
  if (!noise.determined[k]) {
    return StringPrintf("not determined by the data (redundancy %.1f): given", noise.redundancy[k]);
  }
  const bool white = kind == ImuResidualKind::kGyro || kind == ImuResidualKind::kAccel;
  if (white && noise.mode == ImuNoiseMode::kEstimated) {
    return "measured: enters the standard deviations; the given value weights the solve";
  }
  return "measured: weights the solve";
}

}  // namespace

std::string ImuNoiseTableHtml(const ImuNoiseEstimate& noise, const std::string& imu_yaml_path) {
  std::string html = "<table><caption>IMU noise model (--imu-noise " +
                     ImuNoiseModeName(noise.mode) + "), given: " +
                     plot::EscapeXml(NoiseSourceText(imu_yaml_path)) +
                     "</caption>\n<tr><th>density</th><th>given</th><th>measured</th>"
                     "<th>used as weight</th><th>unit</th><th></th></tr>\n";
  for (const DensityRow& row : kDensityRows) {
    html += StringPrintf("<tr><td>%s</td><td>%.6g</td><td>%.6g</td><td>%.6g</td><td>%s</td>",
                         ImuNoiseKey(row.kind),
                         ImuNoiseDensity(noise.given, row.kind),
                         ImuNoiseDensity(noise.measured, row.kind),
                         ImuNoiseDensity(noise.used, row.kind),
                         row.unit) +
            "<td>" + plot::EscapeXml(DensityNote(noise, row.kind)) + "</td></tr>\n";
  }
  // The weights use the IMU's measured rate (sigma = density sqrt(rate)); this is the file's.
  html += StringPrintf("<tr><td>update_rate (as given)</td><td>%.6g</td><td></td><td></td>"
                       "<td>Hz</td><td></td></tr>\n",
                       noise.given.update_rate_hz);
  return html + "</table>\n";
}

void WriteImuNoiseYaml(const ImuNoiseEstimate& noise, YamlWriter* yaml) {
  yaml->BeginMap("imu_noise");
  yaml->Scalar("mode", ImuNoiseModeName(noise.mode));
  for (const DensityRow& row : kDensityRows) {
    const int k = static_cast<int>(row.kind);
    yaml->BeginMap(ImuNoiseKey(row.kind));
    yaml->Scalar("given", ImuNoiseDensity(noise.given, row.kind));
    yaml->Scalar("measured", ImuNoiseDensity(noise.measured, row.kind));
    yaml->Scalar("used", ImuNoiseDensity(noise.used, row.kind));
    yaml->Scalar("determined", noise.mode != ImuNoiseMode::kGiven && noise.determined[k]);
    yaml->Scalar("redundancy", noise.redundancy[k]);
    yaml->EndMap();
  }
  yaml->EndMap();
}

}  // namespace splinecal
