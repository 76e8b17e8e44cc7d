// intrinsics/time_blocks.h: white scores give blocks of about one frame; scores correlated over a
// known time give a correlation length of that order; the 20-block floor caps the length.
#include "splinecal/intrinsics/time_blocks.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace splinecal {
namespace {

// The blocks of n frames at 20 Hz of 3 scores each, AR(1) with coefficient a per frame.
TimeBlocks BlocksOfScores(int n, double a) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  Eigen::Vector3d s = Eigen::Vector3d::Zero();
  std::vector<double> t_s;
  std::vector<Eigen::VectorXd> scores;
  for (int k = 0; k < n; ++k) {
    s = a * s + Eigen::Vector3d(noise(rng), noise(rng), noise(rng));
    t_s.push_back(0.05 * k);
    scores.push_back(s);
  }
  return ChooseTimeBlocks(t_s, scores);
}

TEST(TimeBlocks, WhiteScoresGiveFrameLongBlocks) {
  const TimeBlocks blocks = BlocksOfScores(2000, 0.0);
  EXPECT_LE(blocks.correlation_lag, 2);
  EXPECT_FALSE(blocks.limited_by_min_blocks);
  EXPECT_NEAR(blocks.block_s, 2.0 * 0.05 * blocks.correlation_lag, 1e-9);
}

TEST(TimeBlocks, CorrelatedScoresGiveLongerBlocks) {
  // rho(l) = 0.95^l falls below the band 2 / sqrt(2000) = 0.045 at l = log(0.045) / log(0.95) =
  // 60 frames; the estimate scatters around it.
  const TimeBlocks blocks = BlocksOfScores(2000, 0.95);
  EXPECT_GT(blocks.correlation_lag, 20);
  EXPECT_LT(blocks.correlation_lag, 120);
  // 100 s of frames: at most 100 / 20 = 5 s per block.
  EXPECT_LE(blocks.block_s, 5.0 + 1e-9);
}

TEST(TimeBlocks, TwentyBlocksAtLeast) {
  const TimeBlocks blocks = BlocksOfScores(400, 0.99);  // 20 s, correlated over most of it
  EXPECT_TRUE(blocks.limited_by_min_blocks);
  EXPECT_NEAR(blocks.block_s, 20.0 / kMinBlocks, 1e-9);
}

}  // namespace
}  // namespace splinecal
