#include "splinecal/intrinsics/time_blocks.h"

#include <algorithm>
#include <cmath>

#include "splinecal/median.h"

namespace splinecal {

TimeBlocks ChooseTimeBlocks(const std::vector<double>& t_s,
                            const std::vector<Eigen::VectorXd>& scores) {
  TimeBlocks blocks;
  const int n = static_cast<int>(scores.size());
  if (n < 2 || t_s.size() != scores.size()) return blocks;
  const int p = static_cast<int>(scores.front().size());
  std::vector<double> intervals;
  for (int k = 1; k < n; ++k) intervals.push_back(t_s[k] - t_s[k - 1]);
  const double frame_s = Median(intervals);
  const double span_s = t_s.back() - t_s.front() + frame_s;
  Eigen::MatrixXd z(n, p);
  for (int k = 0; k < n; ++k) z.row(k) = scores[k].transpose();
  for (int j = 0; j < p; ++j) {
    const double norm = z.col(j).norm();
    if (norm > 0.0) z.col(j) /= norm;
  }
  const double band = 2.0 / std::sqrt(static_cast<double>(n));
  blocks.autocorrelation.push_back(1.0);
  int lag = 1;
  for (; lag < n / 2; ++lag) {
    double rho = 0.0;
    for (int j = 0; j < p; ++j) {
      rho += z.col(j).head(n - lag).dot(z.col(j).tail(n - lag));
    }
    rho /= p;
    blocks.autocorrelation.push_back(rho);
    if (rho < band) break;
  }
  blocks.correlation_lag = lag;
  blocks.correlation_length_s = lag * frame_s;
  blocks.block_s = kBlockCorrelationLengths * blocks.correlation_length_s;
  const double longest = span_s / kMinBlocks;
  if (blocks.block_s > longest) {
    blocks.block_s = longest;
    blocks.limited_by_min_blocks = true;
  }
  blocks.block_s = std::max(blocks.block_s, frame_s);
  return blocks;
}

}  // namespace splinecal
