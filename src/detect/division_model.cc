#include "division_model.h"

#include <Eigen/Core>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

#include <opencv2/calib3d.hpp>

namespace splinecal {
namespace {

// [Hartley04] R. Hartley, A. Zisserman, Multiple View Geometry, 2nd ed.

// lambda is searched as kappa = lambda R^2, R the half diagonal; the model's pole (no undistorted
// position) lies R / sqrt(-kappa) from the centre. Measured (docs/detect.md, "Fisheye lenses"):
// -1.64 to -1.24 on the rendered 190 degree double-sphere lens of
// tests/detect/fisheye_recall_test.cc, -0.37 to -0.12 where a model was kept on the resampled
// EuRoC frames of tests/detect/aprilgrid_recall_test.cc.
constexpr double kMinKappa = -3.0;
constexpr double kMaxKappa = 0.3;
constexpr double kKappaStep = 0.25;
// A model is kept only when it at least halves the squared error of the homography alone: with a
// lens the homography describes, lambda would only fit the corners' noise.
constexpr double kMinErrorRatio = 0.5;
// Nor is it searched when the homography alone fits the tags' corners to this RMS [px]: its
// predictions are then as good as the saddle refinement needs (it moves corners by up to 1.5 px
// on the smallest tags), and the search costs about a millisecond per frame.
constexpr double kStraightRmsPx = 0.5;

// The homography from `from` to `to` by the direct linear transform with Hartley's scaling of
// both point sets [Hartley04, alg. 4.2], without the iterative refinement of cv::findHomography:
// the search below fits one per trial lambda, and with the refinement a version of it took the
// detector from 24 to 57 ms on a small-tag frame (bench/detect_bench.cc). False when degenerate.
bool LinearHomography(const std::vector<cv::Point2d>& from,
                      const std::vector<cv::Point2d>& to,
                      Eigen::Matrix3d* H) {
  auto scaling = [](const std::vector<cv::Point2d>& points) {
    cv::Point2d mean(0.0, 0.0);
    for (const cv::Point2d& p : points) mean += p;
    mean *= 1.0 / static_cast<double>(points.size());
    double distance = 0.0;
    for (const cv::Point2d& p : points) distance += cv::norm(p - mean);
    const double s = distance > 0.0 ? std::sqrt(2.0) * points.size() / distance : 1.0;
    Eigen::Matrix3d T;
    T << s, 0.0, -s * mean.x, 0.0, s, -s * mean.y, 0.0, 0.0, 1.0;
    return T;
  };
  const Eigen::Matrix3d Ta = scaling(from), Tb = scaling(to);
  Eigen::Matrix<double, 9, 9> normal = Eigen::Matrix<double, 9, 9>::Zero();
  for (size_t i = 0; i < from.size(); ++i) {
    const Eigen::Vector3d a = Ta * Eigen::Vector3d(from[i].x, from[i].y, 1.0);
    const Eigen::Vector3d b = Tb * Eigen::Vector3d(to[i].x, to[i].y, 1.0);
    Eigen::Matrix<double, 2, 9> rows;
    rows << 0.0, 0.0, 0.0, -b.z() * a.transpose(), b.y() * a.transpose(),
        b.z() * a.transpose(), 0.0, 0.0, 0.0, -b.x() * a.transpose();
    normal += rows.transpose() * rows;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 9, 9>> eigen(normal);
  if (eigen.info() != Eigen::Success) return false;
  const Eigen::Matrix<double, 9, 1> h = eigen.eigenvectors().col(0);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  *H = Tb.inverse() * Hn * Ta;
  return H->allFinite() && std::abs(H->determinant()) > 0.0;
}

// Sum of squared pixel errors of the homography fitted in the undistorted image, measured in the
// image; infinite when the fit or a point's inverse fails.
double SquaredError(const DivisionModel& model,
                    const std::vector<cv::Point2d>& plane,
                    const std::vector<cv::Point2d>& pixels) {
  std::vector<cv::Point2d> undistorted(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (!model.Undistort(pixels[i], &undistorted[i])) return std::numeric_limits<double>::infinity();
  }
  Eigen::Matrix3d H;
  if (!LinearHomography(plane, undistorted, &H)) return std::numeric_limits<double>::infinity();
  double sum = 0.0;
  for (size_t i = 0; i < pixels.size(); ++i) {
    const Eigen::Vector3d m = H * Eigen::Vector3d(plane[i].x, plane[i].y, 1.0);
    cv::Point2d predicted;
    if (!(m.z() != 0.0) || !model.Distort(cv::Point2d(m.x() / m.z(), m.y() / m.z()), &predicted)) {
      return std::numeric_limits<double>::infinity();
    }
    const cv::Point2d d = predicted - pixels[i];
    sum += d.dot(d);
  }
  return sum;
}

}  // namespace

bool DivisionModel::Undistort(const cv::Point2d& p, cv::Point2d* u) const {
  const cv::Point2d d = p - centre;
  const double denominator = 1.0 + lambda * d.dot(d);
  if (!(denominator > 0.0)) return false;
  *u = centre + d * (1.0 / denominator);
  return true;
}

bool DivisionModel::Distort(const cv::Point2d& u, cv::Point2d* p) const {
  const cv::Point2d d = u - centre;
  const double r_u = std::sqrt(d.dot(d));
  if (lambda == 0.0 || r_u == 0.0) {
    *p = u;
    return true;
  }
  const double discriminant = 1.0 - 4.0 * lambda * r_u * r_u;
  if (!(discriminant >= 0.0)) return false;
  const double r = (1.0 - std::sqrt(discriminant)) / (2.0 * lambda * r_u);
  *p = centre + d * (r / r_u);
  return std::isfinite(p->x) && std::isfinite(p->y);
}

bool DivisionModel::Predict(const std::vector<cv::Point2d>& plane,
                            const std::vector<cv::Point2d>& pixels,
                            const std::vector<cv::Point2d>& query,
                            std::vector<cv::Point2d>* predicted) const {
  if (plane.size() < 4 || plane.size() != pixels.size()) return false;
  std::vector<cv::Point2d> undistorted(pixels.size());
  for (size_t i = 0; i < pixels.size(); ++i) {
    if (!Undistort(pixels[i], &undistorted[i])) return false;
  }
  const cv::Mat H = cv::findHomography(plane, undistorted, 0);
  if (H.empty()) return false;
  std::vector<cv::Point2d> mapped;
  cv::perspectiveTransform(query, mapped, H);
  predicted->resize(mapped.size());
  for (size_t i = 0; i < mapped.size(); ++i) {
    if (!Distort(mapped[i], &(*predicted)[i])) return false;
  }
  return true;
}

DivisionModel FitDivisionModel(const CalibrationTarget& target,
                               const std::vector<GridTag>& tags,
                               const cv::Size& size) {
  DivisionModel model;
  model.centre = cv::Point2d(0.5 * (size.width - 1), 0.5 * (size.height - 1));
  if (static_cast<int>(tags.size()) < kMinTagsForDivisionModel) return model;
  const double pitch = 1.0 + target.tag_spacing_ratio;
  std::vector<cv::Point2d> plane, pixels;
  for (const GridTag& tag : tags) {
    for (int k = 0; k < 4; ++k) {
      plane.push_back(TagCorner(target, tag.id, k, pitch));
      pixels.push_back(tag.corners[k]);
    }
  }
  const double half_diagonal_sq = 0.25 * (static_cast<double>(size.width) * size.width +
                                          static_cast<double>(size.height) * size.height);
  auto error_at = [&](double kappa) {
    DivisionModel trial = model;
    trial.lambda = kappa / half_diagonal_sq;
    return SquaredError(trial, plane, pixels);
  };
  // A grid over kappa, then golden-section search between the best point's neighbours.
  double best_kappa = 0.0, best_error = error_at(0.0);
  const double error_without = best_error;
  if (!(error_without > kStraightRmsPx * kStraightRmsPx * pixels.size())) return model;
  for (double kappa = kMinKappa; kappa <= kMaxKappa + 1e-9; kappa += kKappaStep) {
    const double error = error_at(kappa);
    if (error < best_error) {
      best_error = error;
      best_kappa = kappa;
    }
  }
  const double golden = 0.5 * (std::sqrt(5.0) - 1.0);
  double a = best_kappa - kKappaStep, b = best_kappa + kKappaStep;
  double x1 = b - golden * (b - a), x2 = a + golden * (b - a);
  double f1 = error_at(x1), f2 = error_at(x2);
  for (int i = 0; i < 15; ++i) {
    if (f1 < f2) {
      b = x2;
      x2 = x1;
      f2 = f1;
      x1 = b - golden * (b - a);
      f1 = error_at(x1);
    } else {
      a = x1;
      x1 = x2;
      f1 = f2;
      x2 = a + golden * (b - a);
      f2 = error_at(x2);
    }
  }
  if (std::min(f1, f2) < best_error) {
    best_error = std::min(f1, f2);
    best_kappa = f1 < f2 ? x1 : x2;
  }
  if (best_error < kMinErrorRatio * error_without) model.lambda = best_kappa / half_diagonal_sq;
  return model;
}

}  // namespace splinecal
