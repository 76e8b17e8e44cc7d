// The time blocks of the intrinsics' cluster-robust covariance (calibrate_intrinsics.h, step 6),
// chosen from the autocorrelation of the residuals.
//
// Corners of nearby frames share their errors (motion blur, the board's flatness where it is
// seen from the same side, the detector's bias at the same scale): on the EuRoC calibration
// recording the per-view RMS swings between 0.2 and 0.9 px over tens of seconds. A covariance
// from independent pixel noise, or clustered by single frames, then claims ~10x too much
// (docs/intrinsics.md, "Error bars"). The cluster-robust covariance over blocks of time is
// honest when the blocks are nearly independent, i.e. longer than the errors' correlation.
//
// What is correlated is what moves the intrinsics: the score s_k = J_k^T r_k of frame k (the
// gradient its corners exert on the active intrinsics at the solution, each target pose's part
// zero there). With z_kj = s_kj / std_k(s_kj) and frames in time order,
//
//   rho(l) = mean_j  sum_k z_kj z_(k+l)j / sum_k z_kj^2
//
// and the correlation length L is the first lag l at which rho(l) is below the 95% band of a
// white sequence, 2 / sqrt(N) (frames, times the median frame interval in seconds). The blocks
// are kBlockCorrelationLengths x L long (adjacent blocks then share a fraction ~1/that of their
// correlation), but never fewer than kMinBlocks over the recording: the robust estimate rests
// on the number of blocks, and fewer leave its own scatter larger than what it corrects.
#ifndef SPLINECAL_INTRINSICS_TIME_BLOCKS_H_
#define SPLINECAL_INTRINSICS_TIME_BLOCKS_H_

#include <Eigen/Core>
#include <vector>

namespace splinecal {

inline constexpr double kBlockCorrelationLengths = 2.0;
inline constexpr int kMinBlocks = 20;

struct TimeBlocks {
  double block_s = 0.0;               // the chosen block length [s]
  double correlation_length_s = 0.0;  // L [s]
  int correlation_lag = 0;            // L [frames]
  bool limited_by_min_blocks = false;  // the blocks would have been longer
  std::vector<double> autocorrelation;  // rho(0..), until L
};

// t_s: frame times [s], increasing; scores: one per frame, all the same size.
TimeBlocks ChooseTimeBlocks(const std::vector<double>& t_s,
                            const std::vector<Eigen::VectorXd>& scores);

}  // namespace splinecal

#endif  // SPLINECAL_INTRINSICS_TIME_BLOCKS_H_
