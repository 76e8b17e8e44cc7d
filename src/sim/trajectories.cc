#include "splinecal/sim/trajectories.h"

#include <glog/logging.h>

#include <Eigen/Geometry>
#include <cmath>
#include <random>
#include <string>
#include <utility>

#include "splinecal/error.h"
#include "splinecal/units.h"

namespace splinecal {

void SinusoidChannel::Evaluate(double t_s, double* value, double* first, double* second) const {
  double v = offset + rate * t_s;
  double d1 = rate;
  double d2 = 0.0;
  for (const Term& term : terms) {
    const double angle = term.omega_rad_s * t_s + term.phase_rad;
    const double s = std::sin(angle);
    const double c = std::cos(angle);
    v += term.amplitude * s;
    d1 += term.amplitude * term.omega_rad_s * c;
    d2 -= term.amplitude * term.omega_rad_s * term.omega_rad_s * s;
  }
  if (value != nullptr) *value = v;
  if (first != nullptr) *first = d1;
  if (second != nullptr) *second = d2;
}


AnalyticTrajectory::AnalyticTrajectory(std::string name,
                                       std::array<SinusoidChannel, 3> position,
                                       std::array<SinusoidChannel, 3> roll_pitch_yaw)
    : name_(std::move(name)),
      position_(std::move(position)),
      roll_pitch_yaw_(std::move(roll_pitch_yaw)) {}

TrajectoryState AnalyticTrajectory::Evaluate(double t_s) const {
  TrajectoryState state;
  Eigen::Vector3d p_w_s;
  for (int i = 0; i < 3; ++i) {
    position_[i].Evaluate(t_s, &p_w_s[i], &state.v_w[i], &state.a_w[i]);
  }
  double angle[3];
  double angle_rate[3];
  for (int i = 0; i < 3; ++i) roll_pitch_yaw_[i].Evaluate(t_s, &angle[i], &angle_rate[i], nullptr);
  const Eigen::Quaterniond q_x(Eigen::AngleAxisd(angle[0], Eigen::Vector3d::UnitX()));
  const Eigen::Quaterniond q_y(Eigen::AngleAxisd(angle[1], Eigen::Vector3d::UnitY()));
  const Eigen::Quaterniond q_z(Eigen::AngleAxisd(angle[2], Eigen::Vector3d::UnitZ()));
  // R_w_s = Rz(yaw) Ry(pitch) Rx(roll).
  state.T_w_s = SE3d(SO3d::FromQuaternion(q_z * q_y * q_x), p_w_s);
  // w_s = Rx^T Ry^T e_z yaw' + Rx^T e_y pitch' + e_x roll' (file comment of trajectories.h).
  const Eigen::Vector3d yaw_axis_s = (q_y * q_x).conjugate() * Eigen::Vector3d::UnitZ();
  const Eigen::Vector3d pitch_axis_s = q_x.conjugate() * Eigen::Vector3d::UnitY();
  state.w_s = yaw_axis_s * angle_rate[2] + pitch_axis_s * angle_rate[1] +
              Eigen::Vector3d::UnitX() * angle_rate[0];
  return state;
}

SE3d AnalyticTrajectory::Pose(double t_s) const { return Evaluate(t_s).T_w_s; }

std::vector<StampedPose> AnalyticTrajectory::Sample(int64_t start_ns,
                                                    int64_t end_ns,
                                                    int64_t step_ns) const {
  CHECK_GT(step_ns, 0);
  CHECK_GE(end_ns, start_ns);
  std::vector<StampedPose> poses;
  poses.reserve(static_cast<size_t>((end_ns - start_ns) / step_ns + 1));
  for (int64_t k = 0; start_ns + k * step_ns <= end_ns; ++k) {
    StampedPose pose;
    pose.t_ns = start_ns + k * step_ns;
    const SE3d T_w_s = Pose(static_cast<double>(k * step_ns) * 1e-9);
    pose.p = T_w_s.translation();
    pose.q = T_w_s.so3().quaternion();
    poses.push_back(pose);
  }
  return poses;
}

namespace {

using Term = SinusoidChannel::Term;

SinusoidChannel Channel(double offset, double rate, std::vector<Term> terms) {
  SinusoidChannel channel;
  channel.offset = offset;
  channel.rate = rate;
  channel.terms = std::move(terms);
  return channel;
}

}  // namespace

AnalyticTrajectory VioCourseTrajectory() {
  // [seed000 §2], the course's simulator: K = pi / 10; cos(x) = sin(x + pi/2).
  const double k = kPi / 10.0;
  const double quarter = kPi / 2.0;
  return AnalyticTrajectory("vio_course",
                            {Channel(5.0, 0.0, {{15.0, k, quarter}}),
                             Channel(5.0, 0.0, {{20.0, k, 0.0}}),
                             Channel(5.0, 0.0, {{1.0, 10.0 * k, 0.0}})},
                            {Channel(0.0, 0.0, {{0.1, 1.0, quarter}}),  // roll = 0.1 cos t
                             Channel(0.0, 0.0, {{0.2, 1.0, 0.0}}),      // pitch = 0.2 sin t
                             Channel(0.0, k, {})});                     // yaw = K t
}

AnalyticTrajectory Figure8Trajectory() {
  // Lemniscate of Gerono x = a sin(W t), y = a sin(W t) cos(W t) = a/2 sin(2 W t), a = 10 m.
  const double w = 2.0 * kPi / 20.0;
  return AnalyticTrajectory("figure8",
                            {Channel(0.0, 0.0, {{10.0, w, 0.0}}),
                             Channel(0.0, 0.0, {{5.0, 2.0 * w, 0.0}}),
                             Channel(2.0, 0.0, {{0.5, 3.0 * w, 0.0}})},
                            {Channel(0.0, 0.0, {{0.3, 2.0 * w, 0.0}}),
                             Channel(0.0, 0.0, {{0.2, w, 0.5}}),
                             Channel(0.0, 0.0, {{1.2, w, 0.0}})});
}

namespace {

// Uniform in [0, 1) with 53 random bits: the same on every platform (std distributions are not
// specified bit for bit).
double Uniform01(std::mt19937_64* engine) {
  return static_cast<double>((*engine)() >> 11) * 0x1.0p-53;
}

double Uniform(std::mt19937_64* engine, double lo, double hi) {
  return lo + (hi - lo) * Uniform01(engine);
}

// Random terms whose sum of |A_k| omega_k^order is exactly `budget`: random periods, phases and
// weights, then one common scale.
std::vector<Term> RandomTerms(std::mt19937_64* engine,
                              const RandomTrajectoryOptions& options,
                              int order,
                              double budget) {
  std::vector<Term> terms(options.terms_per_channel);
  double sum = 0.0;
  for (Term& term : terms) {
    const double period_s = Uniform(engine, options.min_period_s, options.max_period_s);
    term.omega_rad_s = 2.0 * kPi / period_s;
    term.phase_rad = Uniform(engine, 0.0, 2.0 * kPi);
    term.amplitude = Uniform(engine, 0.2, 1.0);  // Relative weight; scaled below.
    sum += term.amplitude * std::pow(term.omega_rad_s, order);
  }
  for (Term& term : terms) term.amplitude *= budget / sum;
  return terms;
}

}  // namespace

AnalyticTrajectory RandomTrajectory(uint64_t seed, const RandomTrajectoryOptions& options) {
  if (!(options.max_angular_rate_rad_s > 0.0) || !(options.max_acceleration_m_s2 > 0.0) ||
      !(options.min_period_s > 0.0) || !(options.max_period_s >= options.min_period_s) ||
      options.terms_per_channel < 1 || !std::isfinite(options.max_angular_rate_rad_s) ||
      !std::isfinite(options.max_acceleration_m_s2) || !std::isfinite(options.max_period_s) ||
      !options.center_w.allFinite()) {
    throw Error(
        "random trajectory: bounds and periods must be finite and positive (min_period_s <= "
        "max_period_s) and terms_per_channel >= 1");
  }
  std::mt19937_64 engine(seed);
  // Linear acceleration: each axis gets max_acceleration / sqrt(3), so |a_w| <= the bound.
  const double axis_accel = options.max_acceleration_m_s2 / std::sqrt(3.0);
  std::array<SinusoidChannel, 3> position;
  for (int i = 0; i < 3; ++i) {
    position[i] = Channel(options.center_w[i], 0.0, RandomTerms(&engine, options, 2, axis_accel));
  }
  // Angular rate: roll' and pitch' get a third of the bound each; yaw gets a constant drift of at
  // most a sixth and oscillations of a sixth, so |w_s| <= |roll'| + |pitch'| + |yaw'| <= bound.
  const double share = options.max_angular_rate_rad_s / 3.0;
  std::array<SinusoidChannel, 3> roll_pitch_yaw;
  roll_pitch_yaw[0] = Channel(0.0, 0.0, RandomTerms(&engine, options, 1, share));
  roll_pitch_yaw[1] = Channel(0.0, 0.0, RandomTerms(&engine, options, 1, share));
  const double yaw_drift = Uniform(&engine, -0.5, 0.5) * share;
  roll_pitch_yaw[2] = Channel(0.0, yaw_drift, RandomTerms(&engine, options, 1, 0.5 * share));
  return AnalyticTrajectory("random", position, roll_pitch_yaw);
}

AnalyticTrajectory MakeTrajectory(const std::string& name, uint64_t seed) {
  if (name == "vio_course") return VioCourseTrajectory();
  if (name == "figure8") return Figure8Trajectory();
  if (name == "random") return RandomTrajectory(seed);
  throw Error("unknown trajectory '" + name + "' (choose vio_course, figure8 or random)");
}

}  // namespace splinecal
