// Where do the two halves of EuRoC's imu_april recording part? Each mode calibrates subsets of
// the recording's corners (both cameras, default IntrinsicsOptions, 2 threads) and prints, per
// camera, the focal lengths near the axis (fu / (1 + xi) for ds-none, fu for pinhole models),
// the principal point and the reprojection RMS:
//
//   covariates MODEL [HALF]  the views split at the median of their distance, tilt, rotation
//                            rate, corner centroid u and time; HALF 1 or 2 splits one half only
//   alone MODEL              each camera calibrated alone, the whole recording and each half
//   quarters MODEL           each half and its two quarters, with the quarters' normalised
//                            difference per intrinsic
//   outset MODEL DELTA       as covariates, every corner first moved DELTA px away from its tag's
//                            centre in the image (undoing a detector inset constant in pixels)
//
// The data directory is the first of $SPLINECAL_SHARED_DATA_DIR and ../shared/data that exists.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "splinecal/splinecal.h"

namespace {

using namespace splinecal;

constexpr int kWidth = 752, kHeight = 480;
// The middle of the IMU's time range, where docs/calibrate.md cuts the halves.
constexpr int64_t kHalvesCut = 1404733441680300032;

std::string DataDir() {
  const char* env = std::getenv("SPLINECAL_SHARED_DATA_DIR");
  return std::string(env ? env : "../shared/data") + "/euroc_imu_april/";
}

IntrinsicsCameraSpec Spec(const std::string& model) {
  IntrinsicsCameraSpec spec;
  if (!ParseCameraModelName(model, &spec.camera.projection, &spec.camera.distortion)) {
    std::fprintf(stderr, "unknown model %s\n", model.c_str());
    std::exit(2);
  }
  spec.camera.width = kWidth;
  spec.camera.height = kHeight;
  return spec;
}

IntrinsicsResult Calibrate(const std::vector<Observation>& corners, const CalibrationTarget& target,
                           const std::string& model, int cameras = 2) {
  IntrinsicsOptions options;
  options.solver.num_threads = 2;
  return CalibrateIntrinsics(corners, target,
                             std::vector<IntrinsicsCameraSpec>(cameras, Spec(model)), options);
}

// fu / (1 + xi) and its std through the reported covariance (active order fu fv pu pv xi ...).
void PrintCamera(const IntrinsicsCameraResult& c, int n) {
  const Eigen::VectorXd x = c.camera.intrinsics();
  const bool ds = c.active.size() == 6 && c.active[4] == 4;
  const double s = ds ? 1.0 + x(4) : 1.0;
  Eigen::VectorXd g = Eigen::VectorXd::Zero(c.active.size());
  g(0) = 1.0 / s;
  if (ds) g(4) = -x(0) / (s * s);
  const double f_std = c.intrinsics_covariance.size() ? std::sqrt(g.dot(c.intrinsics_covariance * g)) : 0.0;
  std::printf(" | cam%d rms %.3f f %.2f +- %.2f fv %.2f pu %.2f +- %.2f pv %.2f", n,
              c.reprojection_rms_px, x(0) / s, f_std, x(1) / s, x(2), c.intrinsics_std(2), x(3));
}

void Print(const std::string& label, const IntrinsicsResult& r) {
  std::printf("%-20s", label.c_str());
  for (size_t n = 0; n < r.cameras.size(); ++n) PrintCamera(r.cameras[n], static_cast<int>(n));
  std::printf("\n");
}

std::vector<Observation> Keep(const std::vector<Observation>& all, int half) {
  if (half == 0) return all;
  std::vector<Observation> out;
  for (const Observation& o : all) {
    if ((o.t_ns < kHalvesCut) == (half == 1)) out.push_back(o);
  }
  return out;
}

// Each corner moved delta px from the centre of its tag's four observed corners (Kalibr's
// AprilGrid ids: 12 x 12 corners, tag (row / 2, col / 2)); tags seen incompletely stay.
std::vector<Observation> Outset(const std::vector<Observation>& in, double delta) {
  std::map<std::tuple<int64_t, int, int>, std::vector<int>> tags;
  for (int i = 0; i < static_cast<int>(in.size()); ++i) {
    const int row = in[i].point_id / 12, col = in[i].point_id % 12;
    tags[{in[i].t_ns, in[i].cam_id, (row / 2) * 6 + col / 2}].push_back(i);
  }
  std::vector<Observation> out = in;
  for (const auto& [key, members] : tags) {
    if (members.size() != 4) continue;
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();
    for (int i : members) centre += in[i].uv / 4.0;
    for (int i : members) out[i].uv += delta * (in[i].uv - centre).normalized();
  }
  return out;
}

void Covariates(const std::vector<Observation>& corners, const CalibrationTarget& target,
                const std::vector<ImuSample>& imu, const std::string& model) {
  const IntrinsicsResult whole = Calibrate(corners, target, model);
  Print("all", whole);
  std::map<int64_t, double> u_sum, u_count;
  for (const Observation& o : corners) {
    if (o.cam_id != 0) continue;
    u_sum[o.t_ns] += o.uv.x();
    u_count[o.t_ns] += 1.0;
  }
  const char* names[] = {"distance", "tilt", "rate", "centroid_u", "time"};
  std::map<int64_t, std::vector<double>> covariate;
  for (const auto& [t, T_c_t] : whole.target_poses) {
    const Eigen::Vector3d normal = T_c_t.so3().matrix().col(2);
    auto it = std::lower_bound(imu.begin(), imu.end(), t,
                               [](const ImuSample& s, int64_t v) { return s.t_ns < v; });
    if (it == imu.end()) --it;
    covariate[t] = {T_c_t.translation().norm(), std::acos(std::abs(normal.z())) * 180.0 / M_PI,
                    it->gyro.norm() * 180.0 / M_PI,
                    u_count.count(t) ? u_sum[t] / u_count[t] : 0.5 * kWidth, static_cast<double>(t)};
  }
  for (int k = 0; k < 5; ++k) {
    std::vector<double> values;
    for (const auto& [t, c] : covariate) values.push_back(c[k]);
    std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
    const double median = values[values.size() / 2];
    std::vector<Observation> below, above;
    for (const Observation& o : corners) {
      const auto it = covariate.find(o.t_ns);
      if (it != covariate.end()) (it->second[k] < median ? below : above).push_back(o);
    }
    char label[64];
    std::snprintf(label, sizeof(label), "%s < %.4g", names[k], median);
    Print(label, Calibrate(below, target, model));
    std::snprintf(label, sizeof(label), "%s >= %.4g", names[k], median);
    Print(label, Calibrate(above, target, model));
  }
}

void Alone(const std::vector<Observation>& all, const CalibrationTarget& target,
           const std::string& model) {
  for (int cam = 0; cam < 2; ++cam) {
    for (int half = 0; half < 3; ++half) {
      std::vector<Observation> one;
      for (const Observation& o : Keep(all, half)) {
        if (o.cam_id != cam) continue;
        one.push_back(o);
        one.back().cam_id = 0;
      }
      Print("cam" + std::to_string(cam) + (half ? " half " + std::to_string(half) : " all"),
            Calibrate(one, target, model, 1));
    }
  }
}

// Each half and its quarters; then the halves' normalised differences per intrinsic with each
// half's std as reported and floored, where its quarters differ by more than 3 combined std, at
// half their difference (the spread a repeated half would show).
void Quarters(const std::vector<Observation>& all, const CalibrationTarget& target,
              const std::string& model) {
  IntrinsicsResult half[2];
  std::vector<Eigen::VectorXd> floored[2];
  for (int h = 0; h < 2; ++h) {
    const std::vector<Observation> part = Keep(all, h + 1);
    int64_t t0 = part.front().t_ns, t1 = t0;
    for (const Observation& o : part) {
      t0 = std::min(t0, o.t_ns);
      t1 = std::max(t1, o.t_ns);
    }
    const int64_t middle = t0 + (t1 - t0) / 2;
    std::vector<Observation> quarter[2];
    for (const Observation& o : part) quarter[o.t_ns < middle ? 0 : 1].push_back(o);
    const IntrinsicsResult a = Calibrate(quarter[0], target, model);
    const IntrinsicsResult b = Calibrate(quarter[1], target, model);
    half[h] = Calibrate(part, target, model);
    Print("half " + std::to_string(h + 1), half[h]);
    Print(" first quarter", a);
    Print(" second quarter", b);
    for (int n = 0; n < 2; ++n) {
      std::printf("  cam%d quarters' z:", n);
      Eigen::VectorXd stds(a.cameras[n].active.size());
      for (size_t k = 0; k < a.cameras[n].active.size(); ++k) {
        const int j = a.cameras[n].active[k];
        const double difference = a.cameras[n].camera.intrinsics()(j) - b.cameras[n].camera.intrinsics()(j);
        const double z = difference / std::hypot(a.cameras[n].intrinsics_std(j), b.cameras[n].intrinsics_std(j));
        stds(k) = half[h].cameras[n].intrinsics_std(j);
        if (std::abs(z) > 3.0) stds(k) = std::max(stds(k), std::abs(difference) / 2.0);
        std::printf(" %.2f", z);
      }
      std::printf("\n");
      floored[h].push_back(stds);
    }
  }
  double largest[2] = {0.0, 0.0}, sum_sq[2] = {0.0, 0.0};
  int count = 0;
  for (int n = 0; n < 2; ++n) {
    std::printf("halves cam%d z (reported / floored):", n);
    for (size_t k = 0; k < half[0].cameras[n].active.size(); ++k) {
      const int j = half[0].cameras[n].active[k];
      const double difference = half[0].cameras[n].camera.intrinsics()(j) - half[1].cameras[n].camera.intrinsics()(j);
      const double z[2] = {
          difference / std::hypot(half[0].cameras[n].intrinsics_std(j), half[1].cameras[n].intrinsics_std(j)),
          difference / std::hypot(floored[0][n](k), floored[1][n](k))};
      for (int i = 0; i < 2; ++i) {
        largest[i] = std::max(largest[i], std::abs(z[i]));
        sum_sq[i] += z[i] * z[i];
      }
      ++count;
      std::printf(" %.2f/%.2f", z[0], z[1]);
    }
    std::printf("\n");
  }
  std::printf("halves: reported largest |z| %.2f RMS %.2f; floored largest %.2f RMS %.2f\n", largest[0],
              std::sqrt(sum_sq[0] / count), largest[1], std::sqrt(sum_sq[1] / count));
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: intrinsics_splits covariates|alone|quarters|outset MODEL [HALF|DELTA]\n");
    return 2;
  }
  const std::string mode = argv[1], model = argv[2];
  const std::string dir = DataDir();
  const CalibrationTarget target = ReadTargetYaml(dir + "aprilgrid.yaml");
  const std::vector<Observation> all = ReadObservationsCsv(dir + "observations.csv");
  if (mode == "covariates") {
    Covariates(Keep(all, argc > 3 ? std::atoi(argv[3]) : 0), target, ReadEurocImu(dir + "imu0.csv"), model);
  } else if (mode == "outset") {
    Covariates(Outset(all, argc > 3 ? std::atof(argv[3]) : 0.0), target, ReadEurocImu(dir + "imu0.csv"), model);
  } else if (mode == "alone") {
    Alone(all, target, model);
  } else if (mode == "quarters") {
    Quarters(all, target, model);
  } else {
    std::fprintf(stderr, "unknown mode %s\n", mode.c_str());
    return 2;
  }
  return 0;
}
