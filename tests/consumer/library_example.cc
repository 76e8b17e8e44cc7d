// docs/library.md's example, built against the installed library by the Consumer.* tests:
// fit a spline to your own IMU and poses, then query it. argv[1]: a folder with EuRoC's
// imu0.csv, groundtruth.csv and sensor.yaml (the bundled data/euroc_v1_01_easy_20s).
#include <splinecal/splinecal.h>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  const std::string dir = argc > 1 ? argv[1] : "data/euroc_v1_01_easy_20s";
  splinecal::FitOptions options;
  options.model.noise = splinecal::ReadImuYaml(dir + "/sensor.yaml");
  options.model.knot_spacing_s = 0.05;  // 0 would choose it from the data
  const splinecal::FitResult fit = splinecal::Fit(splinecal::ReadEurocImu(dir + "/imu0.csv"),
                                                  splinecal::ReadPoses(dir + "/groundtruth.csv"),
                                                  options);
  std::printf("gyro bias  [%.5f %.5f %.5f] +- %.5f rad/s\n", fit.gyro_bias.x(),
              fit.gyro_bias.y(), fit.gyro_bias.z(), fit.gyro_bias_std.maxCoeff());

  const splinecal::SE3Splined spline = fit.MakeSpline();
  const int64_t t_ns = spline.start_time_ns() + 5'000'000'000;  // 5 s in
  const splinecal::Segment<double> segment = spline.SegmentAtNs(t_ns);
  const Eigen::Vector3d p = spline.Pose(segment).translation();
  const Eigen::Vector3d w = spline.AngularVelocity(segment);
  std::printf("at 5 s: p_w_s [%.3f %.3f %.3f] m, w_s [%.3f %.3f %.3f] rad/s\n", p.x(), p.y(), p.z(),
              w.x(), w.y(), w.z());
  std::printf("library example: %s\n", fit.covariance_ok ? "ok" : "FAILED");
  return fit.covariance_ok ? 0 : 1;
}
