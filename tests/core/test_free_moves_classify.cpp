// Which moves of a mixed recording held their centre (core/free_moves): the moves found in a still mask,
// each classified by the mean of its steps' zero-velocity NIS, and the samples that then hold zero velocity,
// all by hand.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "imucal/core/free_moves.hpp"

namespace imucal {
namespace {

std::vector<ImuSample> samplesAt10Hz(std::size_t n) {
  std::vector<ImuSample> imu(n);
  for (std::size_t k = 0; k < n; ++k) imu[k].t = 0.1 * static_cast<double>(k);
  return imu;
}

TEST(FreeMovesClassify, MovesAreTheRunsThatAreNotStill) {
  const std::vector<bool> still = {true, true, false, false, false, true, false, true, true, false};
  const std::vector<Move> moves = findMoves(samplesAt10Hz(still.size()), still);
  ASSERT_EQ(moves.size(), 3u);
  EXPECT_EQ(moves[0].first, 2u);
  EXPECT_EQ(moves[0].last, 4u);
  EXPECT_DOUBLE_EQ(moves[0].t0, 0.2);
  EXPECT_DOUBLE_EQ(moves[0].t1, 0.4);
  EXPECT_EQ(moves[1].first, 6u);
  EXPECT_EQ(moves[1].last, 6u);
  EXPECT_EQ(moves[2].first, 9u);  // a move the recording ends in
  EXPECT_EQ(moves[2].last, 9u);
  EXPECT_TRUE(findMoves(samplesAt10Hz(3), {true, true, true}).empty());
}

TEST(FreeMovesClassify, AMoveIsHeldWhenItsMeanNisIsWithinTheLimit) {
  const std::vector<bool> still = {true, false, false, false, true, false, false, false, true, false, true};
  std::vector<Move> moves = findMoves(samplesAt10Hz(still.size()), still);
  ASSERT_EQ(moves.size(), 3u);
  // Steps inside the first move (0.1-0.3 s; one ending at its first sample spans the still before it):
  // mean (1 + 2 + 3) / 3 = 2; inside the second (0.5-0.7 s): (30 + 0.5) / 2 = 15.25; none inside the
  // third (0.9 s); the steps at 0.1, 0.4 and 1.0 s are outside every move.
  const std::vector<StepNis> steps = {{0.1, 100.0}, {0.15, 1.0}, {0.2, 2.0},  {0.3, 3.0},
                                      {0.4, 500.0}, {0.6, 30.0}, {0.7, 0.5}, {1.0, 99.0}};
  classifyMoves(moves, steps);
  EXPECT_DOUBLE_EQ(moves[0].velocity_nis, 2.0);
  EXPECT_TRUE(moves[0].held);
  EXPECT_DOUBLE_EQ(moves[1].velocity_nis, 15.25);
  EXPECT_FALSE(moves[1].held);
  EXPECT_TRUE(std::isnan(moves[2].velocity_nis));
  EXPECT_FALSE(moves[2].held);  // nothing showed its centre at rest
  // At the limit still held, above it not.
  classifyMoves(moves, steps, 1.9);
  EXPECT_FALSE(moves[0].held);
  classifyMoves(moves, steps, 15.25);
  EXPECT_TRUE(moves[1].held);

  classifyMoves(moves, steps);
  const std::vector<bool> held = heldSamples(still, moves);
  EXPECT_EQ(held, (std::vector<bool>{true, true, true, true, true, false, false, false, true, false, true}));
}

}  // namespace
}  // namespace imucal
