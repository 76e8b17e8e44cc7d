// Builds a spline through the installed library and checks a closed form: control poses on a
// one-parameter subgroup, T_i = Exp(i dt xi), move with the constant body twist xi, so the
// predicted gyro equals the rotational part of xi. Prints "consumer: ok" on success.
#include <cmath>
#include <cstdio>
#include <vector>

#include <splinecal/imu/imu_model.h>
#include <splinecal/spline/se3_spline.h>

int main() {
  splinecal::Vector6<double> xi;
  xi << 0.5, 0.0, 0.1, 0.2, -0.1, 0.3;  // [rho; phi]
  const double dt_s = 0.1;
  std::vector<splinecal::SE3d> control_poses;
  for (int i = 0; i < 10; ++i) control_poses.push_back(splinecal::SE3d::Exp(xi * (i * dt_s)));
  const splinecal::SE3Splined spline(control_poses, 0, 100000000);

  const splinecal::Segment<double> segment = spline.SegmentAt(0.437);
  Eigen::Vector3d gyro;
  Eigen::Vector3d accel;
  const Eigen::Vector3d zero_bias = Eigen::Vector3d::Zero();
  splinecal::PredictImu(spline, segment, splinecal::GravityWorld(), zero_bias, zero_bias, &gyro,
                        &accel);
  const double error = (gyro - xi.tail<3>()).norm();
  std::printf("gyro = [%.9f %.9f %.9f], |gyro - omega| = %.3g\n", gyro.x(), gyro.y(), gyro.z(),
              error);
  if (!(error < 1e-12)) {
    std::printf("consumer: FAILED\n");
    return 1;
  }
  std::printf("consumer: ok\n");
  return 0;
}
