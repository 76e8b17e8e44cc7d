// docs/detect.md's library example as an installed project uses it: splinecal::detect finds the
// AprilGrid in the bundled EuRoC frame. Arguments: the frame (PNG) and the target YAML.
#include <cstdio>

#include <splinecal/detect/image_file.h>
#include <splinecal/detect/target_detector.h>
#include <splinecal/io/target_yaml.h>

int main(int argc, char** argv) {
  if (argc != 3) {
    std::fprintf(stderr, "usage: detect_example FRAME.png TARGET.yaml\n");
    return 2;
  }
  const splinecal::CalibrationTarget grid = splinecal::ReadTargetYaml(argv[2]);
  splinecal::TargetDetector detector(grid);
  const splinecal::GrayImage image = splinecal::ReadGrayImage(argv[1]);
  const splinecal::TargetDetection detection = detector.Detect(image.view());
  std::printf("%zu corners, first id %lld at (%.3f, %.3f)\n", detection.corners.size(),
              static_cast<long long>(detection.corners.front().point_id),
              detection.corners.front().uv.x(), detection.corners.front().uv.y());
  std::printf(detection.corners.size() == 144 ? "detect example: ok\n"
                                              : "detect example: FAILED\n");
  return detection.corners.size() == 144 ? 0 : 1;
}
