#include "splinecal/detect/saddle_point.h"

#include <cmath>

#include <Eigen/Cholesky>
#include <glog/logging.h>
#include <opencv2/imgproc.hpp>

#include "opencv_view.h"

namespace splinecal {
namespace {

using Vector6d = Eigen::Matrix<double, 6, 1>;
using Matrix6d = Eigen::Matrix<double, 6, 6>;

// The window's fixed part of the weighted least-squares fit: the monomials of every pixel
// offset, their weights, and (A^T W A)^-1 - the same for every window, so each fit is one pass
// over the pixels and one small matrix product.
struct QuadraticFit {
  explicit QuadraticFit(int half_window) : half(half_window) {
    Matrix6d normal = Matrix6d::Zero();
    for (int dy = -half; dy <= half; ++dy) {
      for (int dx = -half; dx <= half; ++dx) {
        const double w = std::exp(-(dx * dx + dy * dy) / (2.0 * half * half));
        Vector6d a;
        a << dx * dx, dx * dy, dy * dy, dx, dy, 1.0;
        weighted_rows.push_back(w * a);
        normal += w * a * a.transpose();
      }
    }
    normal_inverse = normal.ldlt().solve(Matrix6d::Identity());
  }
  int half;
  std::vector<Vector6d> weighted_rows;  // w a, row-major over the window
  Matrix6d normal_inverse;
};

// Fits the quadratic in the window centred on pixel (cx, cy) of `image` (CV_32F); false when it
// is not a saddle. `step` is the saddle relative to the centre.
bool FitSaddle(const cv::Mat& image, const QuadraticFit& fit, int cx, int cy,
               Eigen::Vector2d* step) {
  Vector6d atb = Vector6d::Zero();
  int k = 0;
  for (int dy = -fit.half; dy <= fit.half; ++dy) {
    const float* row = image.ptr<float>(cy + dy);
    for (int dx = -fit.half; dx <= fit.half; ++dx, ++k) {
      atb += static_cast<double>(row[cx + dx]) * fit.weighted_rows[k];
    }
  }
  const Vector6d c = fit.normal_inverse * atb;  // a, b, c, d, e, f
  const double hxx = 2.0 * c[0], hxy = c[1], hyy = 2.0 * c[2];
  const double det = hxx * hyy - hxy * hxy;
  if (!(det < 0.0)) return false;  // an extremum or a flat patch: no junction here
  *step = Eigen::Vector2d((-c[3] * hyy + hxy * c[4]) / det, (-hxx * c[4] + hxy * c[3]) / det);
  return true;
}

// Keys' cubic convolution weights (a = -1/2) of the 4 samples at -1, 0, 1, 2 around a point t
// in [0, 1) past the second one.
void CubicWeights(double t, double w[4]) {
  const double t2 = t * t, t3 = t2 * t;
  w[0] = -0.5 * t3 + t2 - 0.5 * t;
  w[1] = 1.5 * t3 - 2.5 * t2 + 1.0;
  w[2] = -1.5 * t3 + 2.0 * t2 + 0.5 * t;
  w[3] = 0.5 * t3 - 0.5 * t2;
}

// The window of `fit` resampled around the sub-pixel point q by bicubic interpolation in double
// precision (every sample has q's fractional offset, so one set of weights serves all). Bilinear
// interpolation's error on the blurred junction, or OpenCV's remap with its positions rounded
// to 1/32 px, would bias the saddle by some 0.03 px. False when the samples leave the image.
bool ResampleWindow(const cv::Mat& image, const QuadraticFit& fit, const Eigen::Vector2d& q,
                    cv::Mat* patch) {
  const int side = 2 * fit.half + 1;
  const int x0 = static_cast<int>(std::floor(q.x())), y0 = static_cast<int>(std::floor(q.y()));
  if (x0 - fit.half - 1 < 0 || y0 - fit.half - 1 < 0 || x0 + fit.half + 2 >= image.cols ||
      y0 + fit.half + 2 >= image.rows) {
    return false;
  }
  double wx[4], wy[4];
  CubicWeights(q.x() - x0, wx);
  CubicWeights(q.y() - y0, wy);
  patch->create(side, side, CV_32F);
  for (int dy = -fit.half; dy <= fit.half; ++dy) {
    for (int dx = -fit.half; dx <= fit.half; ++dx) {
      double value = 0.0;
      for (int j = 0; j < 4; ++j) {
        const float* row = image.ptr<float>(y0 + dy - 1 + j);
        const int u = x0 + dx - 1;
        value += wy[j] * (wx[0] * row[u] + wx[1] * row[u + 1] + wx[2] * row[u + 2] +
                          wx[3] * row[u + 3]);
      }
      patch->at<float>(dy + fit.half, dx + fit.half) = static_cast<float>(value);
    }
  }
  return true;
}

// Moves the window toward the saddle, at most one pixel per step (far from the junction the
// quadratic is a poor model and its saddle may lie pixels away in the wrong direction), until the
// saddle lies in the window's centre pixel. False when the window leaves the image (with the
// blur's support), the fit is not a saddle, or max_iterations pass.
bool SaddleNear(const cv::Mat& image,
                const QuadraticFit& fit,
                const SaddleOptions& options,
                const Eigen::Vector2d& start,
                Eigen::Vector2d* saddle) {
  const int margin = fit.half + static_cast<int>(std::ceil(3.0 * options.blur_sigma));
  Eigen::Vector2d p = start;
  for (int iteration = 0; iteration < options.max_iterations; ++iteration) {
    if (!std::isfinite(p.x()) || !std::isfinite(p.y())) return false;
    const int cx = static_cast<int>(std::lround(p.x()));
    const int cy = static_cast<int>(std::lround(p.y()));
    if (cx < margin || cy < margin || cx >= image.cols - margin || cy >= image.rows - margin) {
      return false;
    }
    Eigen::Vector2d step;
    if (!FitSaddle(image, fit, cx, cy, &step)) return false;
    if (step.cwiseAbs().maxCoeff() <= 0.5) {
      // The saddle is in the centre pixel. A window on the pixel grid biases the fit by where
      // the saddle falls inside that pixel (up to 0.07 px on real frames: the junction is not a
      // quadratic, and the pixels are symmetric about the window's centre, not the junction);
      // resample the window centred on the estimate until it stops moving.
      Eigen::Vector2d q = Eigen::Vector2d(cx, cy) + step;
      cv::Mat patch;
      for (int refine = 0; refine < options.max_iterations; ++refine) {
        Eigen::Vector2d delta;
        if (!ResampleWindow(image, fit, q, &patch) ||
            !FitSaddle(patch, fit, fit.half, fit.half, &delta) || delta.norm() > 0.5) {
          break;
        }
        q += delta;
        if (delta.norm() < 1e-4) break;
      }
      *saddle = q;
      return true;
    }
    if (step.norm() > 1.0) step.normalize();
    p = Eigen::Vector2d(cx, cy) + step;
    if ((p - start).norm() > options.max_shift) return false;
  }
  return false;
}

}  // namespace

std::vector<bool> RefineSaddlePoints(const GrayImageView& image,
                                     const SaddleOptions& options,
                                     std::vector<Eigen::Vector2d>* points) {
  const cv::Mat pixels = BorrowMat(image);
  CHECK_GE(options.half_window, 1);
  std::vector<bool> converged(points->size(), false);
  if (points->empty()) return converged;

  // Blurred in float: OpenCV blurs 8-bit images in fixed point and rounds the result to whole
  // grey levels, which alone moves a junction by hundredths of a pixel.
  cv::Mat smooth;
  pixels.convertTo(smooth, CV_32F);
  if (options.blur_sigma > 0.0) {
    cv::GaussianBlur(smooth, smooth, cv::Size(0, 0), options.blur_sigma, options.blur_sigma,
                     cv::BORDER_REFLECT);
  }
  // Coarse to fine: a window twice as wide first, since a start a pixel or two inside a black
  // square sees a curvature of one sign only in the small window (an extremum, not a saddle).
  const QuadraticFit coarse(2 * options.half_window);
  const QuadraticFit fine(options.half_window);
  for (size_t i = 0; i < points->size(); ++i) {
    const Eigen::Vector2d start = (*points)[i];
    Eigen::Vector2d p = start;
    const bool near = SaddleNear(smooth, coarse, options, start, &p);
    if (!near) p = start;
    Eigen::Vector2d refined;
    if (SaddleNear(smooth, fine, options, p, &refined) &&
        (refined - start).norm() <= options.max_shift) {
      (*points)[i] = refined;
      converged[i] = true;
    }
  }
  return converged;
}

}  // namespace splinecal
