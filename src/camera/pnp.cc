#include "splinecal/camera/pnp.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <cmath>
#include <limits>
#include <vector>

namespace splinecal {

namespace {

// Smallest singular value of the DLT system relative to the largest below which the geometry is
// degenerate (collinear points, all points on one ray): the solution is then not unique.
constexpr double kMinSingularValueRatio = 1e-10;

// Point sets thinner than this (the RMS distance from their least-squares plane over their RMS
// spread along its shorter in-plane axis) also get the planar closed form on their plane. The
// general DLT recovers the pose from the points' depth, and a nearly flat set gives it little:
// on a 0.66 m board whose corners sit about 1 mm off the plane (a measured or refined target),
// bearing noise of 1 mrad at 1 m is as large as the depth, and the DLT's poses were tens of
// degrees off (EuRoC imu_april, docs/calibrate.md, "Initial guess"). The planar closed form ignores the
// thickness: its pose is off by about the ratio in radians, which the refinement removes.
constexpr double kMaxPlanarThicknessRatio = 0.1;

// The rotation closest to M in the Frobenius norm (det +1).
Eigen::Matrix3d ClosestRotation(const Eigen::Matrix3d& M) {
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  return svd.matrixU() * D * svd.matrixV().transpose();
}

// Hartley's normalisation of N-D points as a homogeneous transform: centroid to 0, mean
// distance sqrt(N).
template <int N>
Eigen::Matrix<double, N + 1, N + 1> Normalisation(
    const std::vector<Eigen::Matrix<double, N, 1>>& points) {
  Eigen::Matrix<double, N, 1> mean = Eigen::Matrix<double, N, 1>::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  double distance = 0.0;
  for (const auto& p : points) distance += (p - mean).norm();
  distance /= static_cast<double>(points.size());
  const double s = distance > 0.0 ? std::sqrt(static_cast<double>(N)) / distance : 1.0;
  Eigen::Matrix<double, N + 1, N + 1> T = Eigen::Matrix<double, N + 1, N + 1>::Identity();
  T.template topLeftCorner<N, N>() *= s;
  T.template topRightCorner<N, 1>() = -s * mean;
  return T;
}

// The DLT solution: the right singular vector of A's smallest singular value. False (with
// `degenerate` as the message) when the next smallest is below kMinSingularValueRatio of the
// largest: the solution is then not unique.
bool NullVector(const Eigen::MatrixXd& A,
                const char* degenerate,
                Eigen::VectorXd* v,
                std::string* message) {
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd& sv = svd.singularValues();
  const Eigen::Index last = A.cols() - 1;
  if (!(sv(last - 1) > kMinSingularValueRatio * sv(0))) {
    *message = degenerate;
    return false;
  }
  *v = svd.matrixV().col(last);
  return true;
}

// The sign of a homogeneous map M (H or P) that puts the points along their bearings rather than
// opposite them: sum_i b_i . (M a_i) > 0 (a majority in words; exact data gives every term > 0).
template <typename Matrix, typename Point>
double AlongBearings(const Matrix& M,
                     const std::vector<Point>& a,
                     const std::vector<Eigen::Vector3d>& b) {
  double sum = 0.0;
  for (size_t i = 0; i < a.size(); ++i) sum += b[i].dot(M * a[i]);
  return sum;
}

bool PlanarPose(const std::vector<Eigen::Vector3d>& p_t,
                const std::vector<Eigen::Vector3d>& b,
                SE3d* T_c_t,
                std::string* message) {
  const int n = static_cast<int>(p_t.size());
  std::vector<Eigen::Vector2d> xy(n);
  std::vector<Eigen::Vector3d> xy1(n);
  for (int i = 0; i < n; ++i) {
    xy[i] = p_t[i].head<2>();
    xy1[i] = Eigen::Vector3d(xy[i].x(), xy[i].y(), 1.0);
  }
  const Eigen::Matrix3d Ta = Normalisation<2>(xy);
  Eigen::MatrixXd A(2 * n, 9);
  for (int i = 0; i < n; ++i) {
    const Eigen::Vector3d a = Ta * xy1[i];
    // b x (H a) = 0: two independent rows (unit bearings need no normalisation).
    A.row(2 * i) << 0.0, 0.0, 0.0, -b[i].z() * a.transpose(), b[i].y() * a.transpose();
    A.row(2 * i + 1) << b[i].z() * a.transpose(), 0.0, 0.0, 0.0, -b[i].x() * a.transpose();
  }
  Eigen::VectorXd h;
  if (!NullVector(A, "degenerate target geometry (collinear points)", &h, message)) return false;
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  Eigen::Matrix3d H = Hn * Ta;
  const double scale = 0.5 * (H.col(0).norm() + H.col(1).norm());
  if (!(scale > 0.0)) {
    *message = "degenerate homography";
    return false;
  }
  H /= scale;
  if (AlongBearings(H, xy1, b) < 0.0) H = -H;  // the points along their bearings
  Eigen::Matrix3d M;
  M.col(0) = H.col(0);
  M.col(1) = H.col(1);
  M.col(2) = H.col(0).cross(H.col(1));
  *T_c_t = SE3d(SO3d::FromMatrix(ClosestRotation(M)), H.col(2));
  return true;
}

bool GeneralPose(const std::vector<Eigen::Vector3d>& p_t,
                 const std::vector<Eigen::Vector3d>& b,
                 SE3d* T_c_t,
                 std::string* message) {
  const int n = static_cast<int>(p_t.size());
  const Eigen::Matrix4d Ta = Normalisation<3>(p_t);
  std::vector<Eigen::Vector4d> homogeneous(n);
  Eigen::MatrixXd A(2 * n, 12);
  for (int i = 0; i < n; ++i) {
    homogeneous[i] = p_t[i].homogeneous();
    const Eigen::Vector4d a = Ta * homogeneous[i];
    A.row(2 * i) << Eigen::RowVector4d::Zero(), -b[i].z() * a.transpose(), b[i].y() * a.transpose();
    A.row(2 * i + 1) << b[i].z() * a.transpose(), Eigen::RowVector4d::Zero(),
        -b[i].x() * a.transpose();
  }
  Eigen::VectorXd p;
  if (!NullVector(
          A, "degenerate target geometry (coplanar or too few independent points)", &p, message)) {
    return false;
  }
  Eigen::Matrix<double, 3, 4> Pn;
  Pn << p(0), p(1), p(2), p(3), p(4), p(5), p(6), p(7), p(8), p(9), p(10), p(11);
  Eigen::Matrix<double, 3, 4> P = Pn * Ta;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd3(P.leftCols<3>());
  const double scale = svd3.singularValues().mean();
  if (!(scale > 0.0)) {
    *message = "degenerate projection matrix";
    return false;
  }
  P /= scale;
  if (AlongBearings(P, homogeneous, b) < 0.0) P = -P;  // the points along their bearings
  *T_c_t = SE3d(SO3d::FromMatrix(ClosestRotation(P.leftCols<3>())), P.col(3));
  return true;
}

// Sum of squared pixel errors; false when a point does not project.
bool Errors(const Camera& camera,
            const SE3d& T_c_t,
            const std::vector<Eigen::Vector3d>& p_t,
            const std::vector<Eigen::Vector2d>& uv,
            double* cost) {
  *cost = 0.0;
  for (size_t i = 0; i < p_t.size(); ++i) {
    Eigen::Vector2d pred;
    if (!camera.Project(T_c_t * p_t[i], &pred)) return false;
    *cost += (pred - uv[i]).squaredNorm();
  }
  return true;
}

// The least-squares plane of the target points: T_t_plane with its origin at their centroid and
// its z axis along the direction of least spread, the points' coordinates in it, and the ratio
// of the RMS distance from the plane to the RMS spread along the plane's shorter in-plane axis.
struct FittedPlane {
  SE3d T_t_plane;
  std::vector<Eigen::Vector3d> p_plane;
  double thickness_ratio = 0.0;
};

FittedPlane FitPlane(const std::vector<Eigen::Vector3d>& p_t) {
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : p_t) centroid += p;
  centroid /= static_cast<double>(p_t.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const Eigen::Vector3d& p : p_t) scatter += (p - centroid) * (p - centroid).transpose();
  // Eigenvalues in increasing order: column 0 is the normal.
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scatter);
  Eigen::Matrix3d R_t_plane;
  R_t_plane << eigen.eigenvectors().col(2), eigen.eigenvectors().col(1),
      eigen.eigenvectors().col(0);
  if (R_t_plane.determinant() < 0.0) R_t_plane.col(2) *= -1.0;
  FittedPlane plane;
  plane.T_t_plane = SE3d(SO3d::FromMatrix(R_t_plane), centroid);
  const SE3d T_plane_t = plane.T_t_plane.inverse();
  for (const Eigen::Vector3d& p : p_t) plane.p_plane.push_back(T_plane_t * p);
  const Eigen::Vector3d spread = eigen.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  plane.thickness_ratio = spread(1) > 0.0 ? spread(0) / spread(1) : 0.0;
  return plane;
}

// Levenberg-Marquardt on the pixel errors from T (right perturbation of T_c_t). False when T
// puts a point outside the camera model's valid region.
bool Refine(const Camera& camera,
            const std::vector<Eigen::Vector3d>& p_t,
            const std::vector<Eigen::Vector2d>& uv,
            int max_iterations,
            SE3d* T_c_t,
            double* cost,
            int* iterations) {
  SE3d& T = *T_c_t;
  if (!Errors(camera, T, p_t, uv, cost)) return false;
  double lambda = 1e-3;
  for (*iterations = 0; *iterations < max_iterations; ++*iterations) {
    Eigen::Matrix<double, 6, 6> JtJ = Eigen::Matrix<double, 6, 6>::Zero();
    Vector6d Jtr = Vector6d::Zero();
    const Eigen::Matrix3d R = T.rotationMatrix();
    for (size_t i = 0; i < p_t.size(); ++i) {
      Eigen::Vector2d pred;
      Eigen::Matrix<double, 2, 3> J_pi;
      camera.Project(T * p_t[i], &pred, &J_pi);
      Eigen::Matrix<double, 2, 6> J;
      J.leftCols<3>() = J_pi * R;
      J.rightCols<3>() = -J_pi * R * Hat(p_t[i]);
      JtJ += J.transpose() * J;
      Jtr += J.transpose() * (pred - uv[i]);
    }
    bool improved = false;
    for (int attempt = 0; attempt < 10 && !improved; ++attempt) {
      Eigen::Matrix<double, 6, 6> A = JtJ;
      A.diagonal() *= (1.0 + lambda);
      const Vector6d step = -A.ldlt().solve(Jtr);
      const SE3d candidate = T * SE3d::Exp(step);
      double candidate_cost = 0.0;
      if (step.allFinite() && Errors(camera, candidate, p_t, uv, &candidate_cost) &&
          candidate_cost < *cost) {
        const bool converged =
            *cost - candidate_cost < 1e-12 * *cost + 1e-20 || step.norm() < 1e-12;
        T = candidate;
        *cost = candidate_cost;
        lambda = std::max(lambda * 0.3, 1e-12);
        improved = true;
        if (converged) *iterations = max_iterations;
      } else {
        lambda *= 10.0;
      }
    }
    if (!improved) break;
  }
  return true;
}

}  // namespace

PnpResult SolvePnp(const Camera& camera,
                   const std::vector<Eigen::Vector3d>& p_t,
                   const std::vector<Eigen::Vector2d>& uv,
                   const PnpOptions& options) {
  PnpResult result;
  const int n = static_cast<int>(p_t.size());
  bool planar = true;
  for (const auto& p : p_t) planar = planar && p.z() == 0.0;
  const int needed = std::max(options.min_points, planar ? 4 : 6);
  if (n != static_cast<int>(uv.size()) || n < needed) {
    result.message =
        "too few points (" + std::to_string(n) + ", need " + std::to_string(needed) + ")";
    return result;
  }
  // The closed form takes the points whose pixels have a bearing (header comment).
  std::vector<Eigen::Vector3d> p_closed_form;
  std::vector<Eigen::Vector3d> bearings;
  for (int i = 0; i < n; ++i) {
    Eigen::Vector3d bearing;
    if (!camera.UnprojectToBearing(uv[i], &bearing)) continue;
    p_closed_form.push_back(p_t[i]);
    bearings.push_back(bearing);
  }
  if (static_cast<int>(bearings.size()) < needed) {
    result.message = "too few pixels unproject (" + std::to_string(bearings.size()) + " of " +
                     std::to_string(n) +
                     "; the others are outside the camera model's valid region)";
    return result;
  }
  // Closed-form candidates (header comment, step 2), each refined; the lowest cost wins.
  std::vector<SE3d> candidates;
  std::string message;
  SE3d T;
  if (planar) {
    if (PlanarPose(p_closed_form, bearings, &T, &message)) candidates.push_back(T);
  } else {
    const FittedPlane plane = FitPlane(p_closed_form);
    if (plane.thickness_ratio < kMaxPlanarThicknessRatio &&
        PlanarPose(plane.p_plane, bearings, &T, &message)) {
      candidates.push_back(T * plane.T_t_plane.inverse());
    }
    if (GeneralPose(p_closed_form, bearings, &T, &message)) candidates.push_back(T);
  }
  if (candidates.empty()) {
    result.message = message;
    return result;
  }
  double best_cost = std::numeric_limits<double>::infinity();
  for (SE3d candidate : candidates) {
    double cost = 0.0;
    int iterations = 0;
    if (!Refine(camera, p_t, uv, options.max_iterations, &candidate, &cost, &iterations) ||
        !(cost < best_cost)) {
      continue;
    }
    best_cost = cost;
    result.ok = true;
    result.T_c_t = candidate;
    result.iterations = iterations;
    result.rms_px = std::sqrt(cost / n);
  }
  if (!result.ok) {
    result.message = "the closed-form pose puts points outside the camera's valid region";
  }
  return result;
}

}  // namespace splinecal
