#include "splinecal/imu/integrate.h"

#include <glog/logging.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "splinecal/enum_names.h"
#include "splinecal/error.h"
#include "splinecal/units.h"

namespace splinecal {

namespace {

constexpr std::array<EnumName<IntegrationMethod>, 3> kIntegrationMethodNames = {{
    {IntegrationMethod::kEuler, "euler"},
    {IntegrationMethod::kMidpoint, "midpoint"},
    {IntegrationMethod::kRk4, "rk4"},
}};

}  // namespace

const char* IntegrationMethodName(IntegrationMethod method) {
  return NameOf(kIntegrationMethodNames, method);
}

IntegrationMethod ParseIntegrationMethod(const std::string& name) {
  IntegrationMethod method;
  if (ValueNamed(kIntegrationMethodNames, name, &method)) return method;
  throw Error("unknown integration method '" + name + "' (choose from " +
              JoinNames(kIntegrationMethodNames, ", ") + ")");
}

std::vector<IntegrationMethod> ParseIntegrationMethods(const std::string& comma_list) {
  std::vector<IntegrationMethod> methods;
  std::stringstream stream(comma_list);
  std::string name;
  while (std::getline(stream, name, ',')) {
    const size_t first = name.find_first_not_of(" \t");
    const size_t last = name.find_last_not_of(" \t");
    name = first == std::string::npos ? "" : name.substr(first, last - first + 1);
    const IntegrationMethod method = ParseIntegrationMethod(name);
    if (std::find(methods.begin(), methods.end(), method) == methods.end()) {
      methods.push_back(method);
    }
  }
  if (methods.empty()) {
    throw Error("no integration method given (choose from " +
                JoinNames(kIntegrationMethodNames, ", ") + ")");
  }
  return methods;
}

NavState NavStateFromGroundTruth(const GroundTruthState& state) {
  NavState nav;
  nav.t_ns = state.t_ns;
  nav.p_w_s = state.p_w_s;
  nav.R_w_s = SO3d::FromQuaternion(state.q_w_s);
  nav.v_w = state.v_w;
  return nav;
}

ImuBias BiasFromGroundTruth(const GroundTruthState& state) {
  ImuBias bias;
  bias.gyro = state.gyro_bias;
  bias.accel = state.accel_bias;
  return bias;
}

GroundTruthState ToGroundTruthState(const NavState& state, const ImuBias& bias) {
  GroundTruthState row;
  row.t_ns = state.t_ns;
  row.p_w_s = state.p_w_s;
  row.q_w_s = state.R_w_s.quaternion();
  row.v_w = state.v_w;
  row.gyro_bias = bias.gyro;
  row.accel_bias = bias.accel;
  return row;
}

namespace internal {

namespace {

// Below this squared angle [rad^2] (t < 0.1 rad) the step helpers use their series to t^8.
// The first dropped terms are t^10 / 3715891200 (cos(t/2)), t^10 / 81749606400 (sin(t/2)/t),
// t^10 / 39916800 (sin t / t), t^10 / 479001600 ((1 - cos t)/t^2) and t^8 / 47900160 (c): at
// t = 0.1 all below 3e-17 relative to the leading term.
constexpr double kStepSeriesAngleSq = 1e-2;

}  // namespace

// The step helpers are inlined into the integration loops (the Impl versions); the public
// functions wrap them for the tests.
namespace {

// Beyond the series range (steps above 0.1 rad): the closed forms, out of line so that the hot
// path stays small.
[[gnu::noinline]] SO3d StepExpLarge(const Eigen::Vector3d& phi) { return SO3d::Exp(phi); }
[[gnu::noinline]] Eigen::Vector3d RotateByExpLarge(const Eigen::Vector3d& phi,
                                                   const Eigen::Vector3d& x) {
  return SO3d::Exp(phi) * x;
}
[[gnu::noinline]] Eigen::Vector3d RightJacobianInverseTimesLarge(const Eigen::Vector3d& phi,
                                                                 const Eigen::Vector3d& w) {
  return RightJacobianInverseSO3(phi) * w;
}

inline SO3d StepExpImpl(const Eigen::Vector3d& phi) {
  const double t2 = phi.squaredNorm();
  if (t2 >= kStepSeriesAngleSq) return StepExpLarge(phi);
  // q = [cos(t/2), sin(t/2)/t phi] (lie/so3.h), Horner in t^2.
  const double w =
      1.0 +
      t2 * (-1.0 / 8.0 + t2 * (1.0 / 384.0 + t2 * (-1.0 / 46080.0 + t2 * (1.0 / 10321920.0))));
  const double k =
      0.5 +
      t2 * (-1.0 / 48.0 + t2 * (1.0 / 3840.0 + t2 * (-1.0 / 645120.0 + t2 * (1.0 / 185794560.0))));
  return SO3d(Eigen::Quaterniond(w, k * phi.x(), k * phi.y(), k * phi.z()));
}

inline Eigen::Vector3d RotateByExpImpl(const Eigen::Vector3d& phi, const Eigen::Vector3d& x) {
  const double t2 = phi.squaredNorm();
  if (t2 >= kStepSeriesAngleSq) return RotateByExpLarge(phi, x);
  // sin t / t and (1 - cos t) / t^2.
  const double a =
      1.0 + t2 * (-1.0 / 6.0 + t2 * (1.0 / 120.0 + t2 * (-1.0 / 5040.0 + t2 * (1.0 / 362880.0))));
  const double b = 0.5 + t2 * (-1.0 / 24.0 +
                               t2 * (1.0 / 720.0 + t2 * (-1.0 / 40320.0 + t2 * (1.0 / 3628800.0))));
  // Rodrigues: Exp(phi) = I + a [phi]x + b [phi]x^2.
  const Eigen::Vector3d phi_x = phi.cross(x);
  return x + a * phi_x + b * phi.cross(phi_x);
}

inline Eigen::Vector3d RightJacobianInverseTimesImpl(const Eigen::Vector3d& phi,
                                                     const Eigen::Vector3d& w) {
  const double t2 = phi.squaredNorm();
  if (t2 >= kStepSeriesAngleSq) return RightJacobianInverseTimesLarge(phi, w);
  // c = 1/12 + t^2/720 + t^4/30240 + t^6/1209600 + O(t^8).
  const double c = 1.0 / 12.0 + t2 * (1.0 / 720.0 + t2 * (1.0 / 30240.0 + t2 * (1.0 / 1209600.0)));
  const Eigen::Vector3d phi_w = phi.cross(w);
  return w + 0.5 * phi_w + c * phi.cross(phi_w);
}

}  // namespace

SO3d StepExp(const Eigen::Vector3d& phi) { return StepExpImpl(phi); }

Eigen::Vector3d RotateByExp(const Eigen::Vector3d& phi, const Eigen::Vector3d& x) {
  return RotateByExpImpl(phi, x);
}

Eigen::Vector3d RightJacobianInverseTimes(const Eigen::Vector3d& phi, const Eigen::Vector3d& w) {
  return RightJacobianInverseTimesImpl(phi, w);
}

}  // namespace internal

namespace {

// Bias-corrected readings at one time.
struct Reading {
  int64_t t_ns;
  Eigen::Vector3d w;  // gyro - b_g
  Eigen::Vector3d a;  // accel - b_a
};

Reading Corrected(const ImuSample& sample, const ImuBias& bias) {
  return Reading{sample.t_ns, sample.gyro - bias.gyro, sample.accel - bias.accel};
}

// Linear interpolation of the readings at t_ns, imu[i - 1].t_ns <= t_ns <= imu[i].t_ns.
Reading Interpolated(const std::vector<ImuSample>& imu,
                     size_t i,
                     int64_t t_ns,
                     const ImuBias& bias) {
  const ImuSample& a = imu[i - 1];
  const ImuSample& b = imu[i];
  if (t_ns == a.t_ns) return Corrected(a, bias);
  if (t_ns == b.t_ns) return Corrected(b, bias);
  const double s = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  ImuSample sample;
  sample.t_ns = t_ns;
  sample.gyro = a.gyro + s * (b.gyro - a.gyro);
  sample.accel = a.accel + s * (b.accel - a.accel);
  return Corrected(sample, bias);
}

// The mutable part of a NavState during integration.
struct Motion {
  Eigen::Vector3d p;
  SO3d R;
  Eigen::Vector3d v;
};

// Composition drifts off the unit sphere by ~eps per product; renormalising every step keeps
// |q| = 1 to rounding over any number of steps.
// One Newton step towards |q| = 1, q *= (3 - |q|^2) / 2: exact to rounding for the ~1e-16
// drift of one product, without a sqrt or a division.
SO3d Renormalized(const SO3d& R) {
  const Eigen::Quaterniond& q = R.quaternion();
  return SO3d(Eigen::Quaterniond(q.coeffs() * (1.5 - 0.5 * q.squaredNorm())));
}

// [seed000 §2] Euler.
void EulerStep(const Reading& r0, const Eigen::Vector3d& g_w, double h, Motion* m) {
  const Eigen::Vector3d a_w = m->R * r0.a + g_w;
  m->p += m->v * h + (0.5 * h * h) * a_w;
  m->v += a_w * h;
  m->R = Renormalized(m->R * internal::StepExpImpl(r0.w * h));
}

// [seed000 §2] midpoint: mean rate, mean of the two ends' world accelerations.
void MidpointStep(
    const Reading& r0, const Reading& r1, const Eigen::Vector3d& g_w, double h, Motion* m) {
  const SO3d R1 = Renormalized(m->R * internal::StepExpImpl((0.5 * h) * (r0.w + r1.w)));
  const Eigen::Vector3d a_w = 0.5 * (m->R * r0.a + R1 * r1.a) + g_w;
  m->p += m->v * h + (0.5 * h * h) * a_w;
  m->v += a_w * h;
  m->R = R1;
}

// Classical RK4 on (theta, v, p) with R = R_k Exp(theta) (see integrate.h). The stage
// accelerations are k_vi = R_k b_i + g with body-frame b_i = Exp(th_i) a(s_i), so the sums
//   p += h/6 (k_p1 + 2 k_p2 + 2 k_p3 + k_p4) = h v + h^2/6 (k_v1 + k_v2 + k_v3)
//   v += h/6 (k_v1 + 2 k_v2 + 2 k_v3 + k_v4)
// need R_k only twice.
void Rk4Step(const Reading& r0,
             const Reading& r_m,
             const Reading& r1,
             const Eigen::Vector3d& g_w,
             double h,
             Motion* m) {
  const Eigen::Vector3d& w_m = r_m.w;
  const Eigen::Vector3d& a_m = r_m.a;
  // Stage 1 at s = 0: theta = 0, Jr^-1 = I.
  const Eigen::Vector3d& k_th1 = r0.w;
  const Eigen::Vector3d& b1 = r0.a;
  // Stage 2 at s = h/2.
  const Eigen::Vector3d th2 = (0.5 * h) * k_th1;
  const Eigen::Vector3d k_th2 = internal::RightJacobianInverseTimesImpl(th2, w_m);
  const Eigen::Vector3d b2 = internal::RotateByExpImpl(th2, a_m);
  // Stage 3 at s = h/2.
  const Eigen::Vector3d th3 = (0.5 * h) * k_th2;
  const Eigen::Vector3d k_th3 = internal::RightJacobianInverseTimesImpl(th3, w_m);
  const Eigen::Vector3d b3 = internal::RotateByExpImpl(th3, a_m);
  // Stage 4 at s = h.
  const Eigen::Vector3d th4 = h * k_th3;
  const Eigen::Vector3d k_th4 = internal::RightJacobianInverseTimesImpl(th4, r1.w);
  const Eigen::Vector3d b4 = internal::RotateByExpImpl(th4, r1.a);
  const SO3d& R = m->R;
  const Eigen::Vector3d sum_p = R * (b1 + b2 + b3) + 3.0 * g_w;               // k_v1 + k_v2 + k_v3
  const Eigen::Vector3d sum_v = R * (b1 + 2.0 * (b2 + b3) + b4) + 6.0 * g_w;  // weighted sum
  const double sixth_h = h * (1.0 / 6.0);
  const Eigen::Vector3d theta = sixth_h * (k_th1 + 2.0 * (k_th2 + k_th3) + k_th4);
  m->p += h * m->v + (sixth_h * h) * sum_p;
  m->v += sixth_h * sum_v;
  m->R = Renormalized(R * internal::StepExpImpl(theta));
}

// The gyro reading at the middle of the step [r0.t_ns, r1.t_ns], which lies inside the sample
// interval [imu[i-1], imu[i]]: the cubic through imu[i-2..i+1] (Lagrange; the quadratic or the
// line through the samples that exist at the ends of the data), minus the bias. Error O(h^4)
// for a smooth rate (O(h^2) across a jump of d2w/dt2, as at the knots of a cubic spline),
// against O(h^2) for the average of the two ends (integrate.h explains why RK4 needs it).
Eigen::Vector3d MidGyro(const std::vector<ImuSample>& imu,
                        size_t i,
                        const Reading& r0,
                        const Reading& r1,
                        const ImuBias& bias) {
  const size_t first = i >= 2 ? i - 2 : i - 1;
  const size_t last = std::min(i + 1, imu.size() - 1);
  const int64_t origin = imu[i - 1].t_ns;
  if (last - first == 3 && r0.t_ns == origin && r1.t_ns == imu[i].t_ns &&
      imu[i - 1].t_ns - imu[i - 2].t_ns == imu[i].t_ns - imu[i - 1].t_ns &&
      imu[i + 1].t_ns - imu[i].t_ns == imu[i].t_ns - imu[i - 1].t_ns) {
    // Uniform samples, a whole interval: the cubic's weights at the middle are (-1, 9, 9, -1)/16.
    return (9.0 * (imu[i - 1].gyro + imu[i].gyro) - (imu[i - 2].gyro + imu[i + 1].gyro)) / 16.0 -
           bias.gyro;
  }
  const double x = 0.5 * static_cast<double>((r0.t_ns - origin) + (r1.t_ns - origin));
  Eigen::Vector3d gyro = Eigen::Vector3d::Zero();
  for (size_t j = first; j <= last; ++j) {
    double weight = 1.0;  // Lagrange basis polynomial of node j at x.
    const double x_j = static_cast<double>(imu[j].t_ns - origin);
    for (size_t l = first; l <= last; ++l) {
      if (l == j) continue;
      const double x_l = static_cast<double>(imu[l].t_ns - origin);
      weight *= (x - x_l) / (x_j - x_l);
    }
    gyro += weight * imu[j].gyro;
  }
  return gyro - bias.gyro;  // The weights sum to 1.
}

template <IntegrationMethod kMethod>
void Step(const std::vector<ImuSample>& imu,
          size_t i,
          const Reading& r0,
          const Reading& r1,
          const ImuBias& bias,
          const Eigen::Vector3d& g_w,
          Motion* m) {
  const double h = static_cast<double>(r1.t_ns - r0.t_ns) * 1e-9;
  if constexpr (kMethod == IntegrationMethod::kEuler) {
    EulerStep(r0, g_w, h, m);
  } else if constexpr (kMethod == IntegrationMethod::kMidpoint) {
    MidpointStep(r0, r1, g_w, h, m);
  } else {
    Reading mid;
    mid.t_ns = r0.t_ns + (r1.t_ns - r0.t_ns) / 2;
    mid.w = MidGyro(imu, i, r0, r1, bias);
    mid.a = 0.5 * (r0.a + r1.a);
    Rk4Step(r0, mid, r1, g_w, h, m);
  }
}

NavState ToNavState(int64_t t_ns, const Motion& m) {
  NavState state;
  state.t_ns = t_ns;
  state.p_w_s = m.p;
  state.R_w_s = m.R;
  state.v_w = m.v;
  return state;
}

template <IntegrationMethod kMethod>
NavState Integrate(const std::vector<ImuSample>& imu,
                   const NavState& start,
                   int64_t end_ns,
                   const ImuBias& bias,
                   const Eigen::Vector3d& g_w,
                   std::vector<NavState>* trajectory) {
  // First sample strictly after the start.
  auto after = std::upper_bound(
      imu.begin(), imu.end(), start.t_ns, [](int64_t t, const ImuSample& s) { return t < s.t_ns; });
  size_t i = static_cast<size_t>(after - imu.begin());
  Motion m{start.p_w_s, start.R_w_s, start.v_w};
  if (trajectory != nullptr) trajectory->push_back(start);
  if (end_ns == start.t_ns) return start;
  // start.t_ns is in [imu[i-1].t_ns, imu[i].t_ns); i < imu.size() since end_ns > start.t_ns.
  Reading previous = Interpolated(imu, i, start.t_ns, bias);
  for (; i < imu.size() && imu[i].t_ns < end_ns; ++i) {
    const Reading next = Corrected(imu[i], bias);
    Step<kMethod>(imu, i, previous, next, bias, g_w, &m);
    if (trajectory != nullptr) trajectory->push_back(ToNavState(next.t_ns, m));
    previous = next;
  }
  // The last step ends at end_ns, on or before imu[i].
  const Reading last = Interpolated(imu, i, end_ns, bias);
  Step<kMethod>(imu, i, previous, last, bias, g_w, &m);
  const NavState end = ToNavState(end_ns, m);
  if (trajectory != nullptr) trajectory->push_back(end);
  return end;
}

}  // namespace

NavState IntegrateImu(const std::vector<ImuSample>& imu,
                      const NavState& start,
                      int64_t end_ns,
                      const ImuBias& bias,
                      const Eigen::Vector3d& g_w,
                      IntegrationMethod method,
                      std::vector<NavState>* trajectory) {
  if (imu.size() < 2) throw Error("IMU integration needs at least 2 IMU samples");
  if (start.t_ns < imu.front().t_ns || start.t_ns > imu.back().t_ns) {
    throw Error("IMU integration: start time " + std::to_string(start.t_ns) +
                " ns is outside the IMU data [" + std::to_string(imu.front().t_ns) + ", " +
                std::to_string(imu.back().t_ns) + "] ns");
  }
  if (end_ns < start.t_ns || end_ns > imu.back().t_ns) {
    throw Error("IMU integration: end time " + std::to_string(end_ns) +
                " ns is outside [start, last IMU sample] = [" + std::to_string(start.t_ns) + ", " +
                std::to_string(imu.back().t_ns) + "] ns");
  }
  if (trajectory != nullptr) {
    const auto first =
        std::lower_bound(imu.begin(), imu.end(), start.t_ns, [](const ImuSample& s, int64_t t) {
          return s.t_ns < t;
        });
    const auto last = std::lower_bound(
        imu.begin(), imu.end(), end_ns, [](const ImuSample& s, int64_t t) { return s.t_ns < t; });
    if (last >= first) {
      trajectory->reserve(trajectory->size() + static_cast<size_t>(last - first) + 2);
    }
  }
  switch (method) {
    case IntegrationMethod::kEuler:
      return Integrate<IntegrationMethod::kEuler>(imu, start, end_ns, bias, g_w, trajectory);
    case IntegrationMethod::kMidpoint:
      return Integrate<IntegrationMethod::kMidpoint>(imu, start, end_ns, bias, g_w, trajectory);
    case IntegrationMethod::kRk4:
      return Integrate<IntegrationMethod::kRk4>(imu, start, end_ns, bias, g_w, trajectory);
  }
  LOG(FATAL) << "unknown IntegrationMethod " << static_cast<int>(method);
  return start;
}

NavState InterpolateNavState(const std::vector<NavState>& trajectory, int64_t t_ns) {
  if (trajectory.empty() || t_ns < trajectory.front().t_ns || t_ns > trajectory.back().t_ns) {
    throw Error("interpolation time " + std::to_string(t_ns) +
                " ns is outside the integrated trajectory");
  }
  auto after = std::lower_bound(
      trajectory.begin(), trajectory.end(), t_ns, [](const NavState& s, int64_t t) {
        return s.t_ns < t;
      });
  if (after->t_ns == t_ns) return *after;
  const NavState& a = *(after - 1);
  const NavState& b = *after;
  const double h = static_cast<double>(b.t_ns - a.t_ns) * 1e-9;
  const double s = static_cast<double>(t_ns - a.t_ns) / static_cast<double>(b.t_ns - a.t_ns);
  // Cubic Hermite basis on [0, 1].
  const double s2 = s * s;
  const double s3 = s2 * s;
  const double h00 = 2.0 * s3 - 3.0 * s2 + 1.0;
  const double h10 = s3 - 2.0 * s2 + s;
  const double h01 = -2.0 * s3 + 3.0 * s2;
  const double h11 = s3 - s2;
  NavState state;
  state.t_ns = t_ns;
  state.p_w_s = h00 * a.p_w_s + (h10 * h) * a.v_w + h01 * b.p_w_s + (h11 * h) * b.v_w;
  state.v_w = a.v_w + s * (b.v_w - a.v_w);
  state.R_w_s = a.R_w_s * SO3d::Exp(s * (a.R_w_s.inverse() * b.R_w_s).Log());
  return state;
}

DriftMetrics ComputeDrift(const std::vector<NavState>& trajectory,
                          const std::vector<GroundTruthState>& ground_truth) {
  DriftMetrics metrics;
  if (trajectory.empty()) throw Error("drift: the integrated trajectory is empty");
  double sum_sq = 0.0;
  for (const GroundTruthState& truth : ground_truth) {
    if (truth.t_ns < trajectory.front().t_ns || truth.t_ns > trajectory.back().t_ns) continue;
    const NavState state = InterpolateNavState(trajectory, truth.t_ns);
    const double position_error = (state.p_w_s - truth.p_w_s).norm();
    sum_sq += position_error * position_error;
    ++metrics.num_compared;
    metrics.final_position_error_m = position_error;
    const SO3d R_gt = SO3d::FromQuaternion(truth.q_w_s);
    metrics.final_rotation_error_deg = (R_gt.inverse() * state.R_w_s).Log().norm() * 180.0 / kPi;
    metrics.final_t_ns = truth.t_ns;
  }
  if (metrics.num_compared == 0) {
    throw Error("drift: no ground-truth time falls inside the integrated trajectory [" +
                std::to_string(trajectory.front().t_ns) + ", " +
                std::to_string(trajectory.back().t_ns) + "] ns");
  }
  metrics.ate_rmse_m = std::sqrt(sum_sq / static_cast<double>(metrics.num_compared));
  return metrics;
}

}  // namespace splinecal
