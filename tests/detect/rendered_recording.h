// A simulated camera-IMU recording turned into what a user has: image files of the target
// (tests/detect/render_aprilgrid.h) and an IMU file, with the truth kept beside them, for the tests
// that run `splinecal detect` and what follows on them (detect_calibrate_test.cc,
// fisheye_chain_slow_test.cc).
#ifndef SPLINECAL_TESTS_DETECT_RENDERED_RECORDING_H_
#define SPLINECAL_TESTS_DETECT_RENDERED_RECORDING_H_

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <opencv2/imgcodecs.hpp>

#include "calib/calibrate_test_scenario.h"
#include "detect/render_aprilgrid.h"
#include "splinecal/io/camchain_yaml.h"
#include "splinecal/io/euroc.h"
#include "splinecal/io/observations_csv.h"
#include "splinecal/units.h"
#include "testing/run_tool.h"
#include "testing/temp_dir.h"

namespace splinecal {
namespace testing {

// A 512 x 512 double-sphere fisheye of about 190 degrees, like TUM-VI's cameras.
inline Camera TumViLikeFisheye() {
  Camera camera;
  camera.projection = ProjectionModel::kDoubleSphere;
  camera.distortion = DistortionModel::kNone;
  camera.fu = 158.3;
  camera.fv = 158.3;
  camera.pu = 254.9;
  camera.pv = 256.9;
  camera.projection_params << -0.18, 0.59;  // xi, alpha
  camera.width = 512;
  camera.height = 512;
  return camera;
}

// A scenario (calib/calibrate_test_scenario.h) of `duration_s` for rendering: exact corners (the
// images carry the noise) and a global shutter (each frame is one homography of the plane's rays).
inline ScenarioOptions RenderedScenarioOptions(double duration_s) {
  ScenarioOptions o;
  o.duration_s = duration_s;
  o.pixel_noise_px = 0.0;
  o.line_delay_s = 0.0;
  return o;
}

struct RenderedRecording {
  std::string target_path;  // the target's YAML
  std::string imu_path;    // EuRoC imu0/data.csv
  std::string images_dir;  // cam0/<t_ns>.png
  int frames = 0;
  std::map<std::pair<int64_t, int64_t>, Eigen::Vector2d> truth;  // (t_ns, corner id) -> pixel
};

// The target's YAML for `splinecal`'s --target.
inline std::string AprilGridYaml(const CalibrationTarget& target) {
  std::ostringstream yaml;
  yaml << "target_type: aprilgrid\ntagCols: " << target.grid_cols << "\ntagRows: "
       << target.grid_rows << "\ntagSize: " << target.tag_size_m
       << "\ntagSpacing: " << target.tag_spacing_ratio << "\n";
  return yaml.str();
}

// Writes the target, the IMU and every frame of `s` that sees at least 8 corners (lens blur
// 0.5 px, noise 2 grey levels) under `dir`.
inline RenderedRecording RenderRecording(const CalibrationScenario& s, const TempDir& dir) {
  RenderedRecording r;
  r.target_path = dir.Write("april.yaml", AprilGridYaml(s.target));
  std::ostringstream imu;
  WriteEurocImu(s.imu, &imu);
  r.imu_path = dir.Write("imu0/data.csv", imu.str());
  r.images_dir = dir.File("cam0");
  std::filesystem::create_directories(r.images_dir);
  const AprilGridTexture texture(s.target, 10);
  const PlanarViewRenderer renderer(s.truth[0].camera, texture);
  for (const ObservationFrame& frame : GroupIntoFrames(s.observations)) {
    if (frame.observations.size() < 8) continue;
    const GrayImage image = renderer.Render(frame.observations, s.target, 0.5, 2.0, r.frames);
    const cv::Mat pixels(image.height, image.width, CV_8UC1,
                         const_cast<uint8_t*>(image.pixels.data()));
    EXPECT_TRUE(cv::imwrite(r.images_dir + "/" + std::to_string(frame.t_ns) + ".png", pixels));
    for (const Observation& ob : frame.observations) r.truth[{ob.t_ns, ob.point_id}] = ob.uv;
    ++r.frames;
  }
  return r;
}

struct CornerErrors {
  double rms_px = 0.0;
  double max_px = 0.0;
};

// The detected corners against the truth; a corner the camera did not see fails the test.
inline CornerErrors ErrorsAgainstTruth(const std::vector<Observation>& found,
                                       const RenderedRecording& r) {
  CornerErrors e;
  double sum_squares = 0.0;
  for (const Observation& ob : found) {
    const auto it = r.truth.find({ob.t_ns, ob.point_id});
    if (it == r.truth.end()) {
      ADD_FAILURE() << "a corner the camera did not see: t " << ob.t_ns << " id " << ob.point_id;
      continue;
    }
    const double error = (ob.uv - it->second).norm();
    sum_squares += error * error;
    e.max_px = std::max(e.max_px, error);
  }
  if (!found.empty()) e.rms_px = std::sqrt(sum_squares / found.size());
  return e;
}

struct DetectedCorners {
  std::string observations_path;
  size_t found = 0;
  CornerErrors errors;
};

// `splinecal detect` on the recording's images into `out`, and its corners against the truth,
// printed. Fails the test when the tool does.
inline DetectedCorners DetectAgainstTruth(const RenderedRecording& r, const std::string& out) {
  DetectedCorners d;
  const ToolResult run = RunTool(
      {"detect", "--images", r.images_dir, "--target", r.target_path, "--quiet", "--out", out});
  EXPECT_EQ(run.exit_code, 0) << run.err;
  if (run.exit_code != 0) return d;
  d.observations_path = out + "/observations.csv";
  const std::vector<Observation> found = ReadObservationsCsv(d.observations_path);
  d.found = found.size();
  d.errors = ErrorsAgainstTruth(found, r);
  std::printf("detect: %zu of %zu corners in %d frames, error RMS %.4f px, max %.4f px\n",
              d.found, r.truth.size(), r.frames, d.errors.rms_px, d.errors.max_px);
  return d;
}

struct RigError {
  double rotation_deg = 0.0;
  double translation_m = 0.0;
  double time_offset_s = 0.0;
};

// `splinecal calibrate` of the recording's IMU and `observations` with `camchain` into `out`, and
// the error of its cam0 against the truth, printed. Fails the test when the tool does.
inline RigError CalibrateAgainstTruth(const CalibrationScenario& s, const RenderedRecording& r,
                                      const std::string& observations,
                                      const std::string& camchain, const std::string& out) {
  const ToolResult c =
      RunTool({"calibrate", "--imu", r.imu_path, "--observations", observations, "--camchain",
               camchain, "--target", r.target_path, "--threads", "2", "--quiet", "--out", out});
  EXPECT_EQ(c.exit_code, 0) << c.err;
  if (c.exit_code != 0) return {1e9, 1e9, 1e9};
  const Camchain estimate = ReadCamchainYaml(out + "/camchain-imucam.yaml");
  const SE3d error = s.truth[0].T_cam_imu.inverse() * estimate.at(0).T_cam_imu;
  const RigError e{error.so3().Log().norm() * kRadToDeg, error.translation().norm(),
                   estimate.at(0).time_offset_s - s.truth[0].time_offset_s};
  std::printf("calibrate: rotation %.4f deg, translation %.3f mm, time offset %.4f ms\n",
              e.rotation_deg, 1e3 * e.translation_m, 1e3 * e.time_offset_s);
  return e;
}

// calibrate's accuracy targets, 0.05 deg, 2 mm, 0.1 ms (docs/calibrate.md, "Tests";
// tests/calib/calibrate_test_checks.h).
inline void ExpectWithinCalibrateTargets(const RigError& e) {
  EXPECT_LT(e.rotation_deg, 0.05);
  EXPECT_LT(e.translation_m, 0.002);
  EXPECT_LT(std::abs(e.time_offset_s), 1e-4);
}

}  // namespace testing
}  // namespace splinecal

#endif  // SPLINECAL_TESTS_DETECT_RENDERED_RECORDING_H_
