// `splinecal export`: a calibration folder (calibrate's, or intrinsics' for the camera-only
// formats) written in the files of OpenVINS, VINS-Mono / VINS-Fusion, basalt or Kalibr
// (io/calibration_export.h; docs/export.md has every field per format).
#include <gflags/gflags.h>

#include <cstdio>

#include "splinecal/cli/command.h"
#include "splinecal/cli/commands.h"
#include "splinecal/cli/common_flags.h"
#include "splinecal/error.h"
#include "splinecal/io/calibration_export.h"
#include "splinecal/io/output_dir.h"

DEFINE_string(from, "", "Calibration folder: calibrate's (or intrinsics') --out [path]");
DEFINE_string(format, "", "openvins, vins, basalt or kalibr");

namespace splinecal {
namespace cli {

namespace {

struct ExportInputs {
  CalibrationExport calibration;
  ExportFormat format = ExportFormat::kKalibr;
};

ExportInputs ReadExportInputs() {
  ExportInputs in;
  const std::string& format = RequiredFlag("format", FLAGS_format);
  if (!ParseExportFormat(format, &in.format)) {
    throw Error("--format " + format + ": expected one of " + ExportFormatNames());
  }
  in.calibration = ReadCalibrationForExport(RequiredFlag("from", FLAGS_from), FLAGS_imu_yaml);
  if (FLAGS_imu_topic.empty() || FLAGS_imu_topic[0] != '/') {
    throw Error("--imu-topic '" + FLAGS_imu_topic + "': a ROS topic starts with '/'");
  }
  in.calibration.imu_topic = FLAGS_imu_topic;
  RequiredFlag("out", FLAGS_out);
  // Every refusal (a model the format cannot hold) happens here, before anything is written.
  ExportCalibration(in.calibration, in.format);
  return in;
}

int RunExport() {
  const ExportInputs in = ReadExportInputs();
  OutputDir output(FLAGS_out);
  const std::vector<OutputFile> files = ExportCalibration(in.calibration, in.format);
  output.WriteFiles(files);
  output.Commit();
  if (!Quiet()) {
    std::printf("%s: %zu camera(s)%s\n",
                ExportFormatName(in.format).c_str(),
                in.calibration.camchain.size(),
                in.calibration.has_imu ? " and the IMU" : " (no IMU)");
    if (in.calibration.has_imu) {
      std::printf("IMU noise from %s, %.6g Hz\n",
                  in.calibration.imu_noise_source.c_str(),
                  in.calibration.imu_noise.update_rate_hz);
    }
    for (const OutputFile& file : files) {
      std::printf("wrote %s/%s\n", FLAGS_out.c_str(), file.path.c_str());
    }
  }
  return 0;
}

}  // namespace

Command ExportCommand() {
  return {"export",
          "write a calibration for OpenVINS, VINS, basalt or Kalibr",
          "splinecal export --from DIR --format openvins|vins|basalt|kalibr --out DIR\n"
          "    [--imu-yaml FILE] [--imu-topic TOPIC]",
          "Reads a calibration folder - calibrate's (camchain-imucam.yaml, result.yaml) or\n"
          "intrinsics' (camchain.yaml; kalibr only) - and writes it in the files the chosen\n"
          "estimator reads: OpenVINS' kalibr_imucam_chain.yaml and kalibr_imu_chain.yaml,\n"
          "VINS-Mono / VINS-Fusion's vins_config.yaml and camN.yaml, basalt's calibration.json,\n"
          "or Kalibr's camchain-imucam.yaml and imu.yaml. The IMU noise comes from --imu-yaml,\n"
          "else DIR/imu.yaml, else the densities calibrate used (result.yaml). A camera model\n"
          "the format cannot hold is refused, naming the ones it can.",
          {{"from", ""},
           {"format", ""},
           {"out", ""},
           {"imu_yaml", "IMU noise densities and rate, Kalibr imu.yaml (default: DIR/imu.yaml, "
                        "else result.yaml's) [path]"},
           {"imu_topic", "The IMU's ROS topic, written where a format names it"}},
          &RunExport,
          [] { ReadExportInputs(); }};
}

}  // namespace cli
}  // namespace splinecal
