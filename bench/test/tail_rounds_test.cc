// bench/support/tail_rounds: the tails verdict of issue 33 point 1.
#include "tail_rounds.h"

#include <gtest/gtest.h>

namespace hubrt::bench {
namespace {

TEST(TailRounds, TheVerdictIsTheMedianOfTheRoundsRatiosWithTheirSpread) {
  // Baseline p95 1 and p99 2 in every round; the subject's ratios 1.0, 1.2, 1.1, 0.9, 1.3.
  std::vector<RoundTails> rounds;
  for (double ratio : {1.0, 1.2, 1.1, 0.9, 1.3}) rounds.push_back({ratio, 2 * ratio, 1.0, 2.0});
  const TailVerdict v = judge_tails(rounds);
  ASSERT_EQ(v.ratio_p95.size(), 5u);
  EXPECT_DOUBLE_EQ(v.ratio_p95[1], 1.2);
  EXPECT_DOUBLE_EQ(v.ratio_p99[3], 0.9);
  EXPECT_EQ(v.judged_rounds, 5u);
  EXPECT_DOUBLE_EQ(v.median_p95, 1.1);
  EXPECT_DOUBLE_EQ(v.median_p99, 1.1);
  EXPECT_DOUBLE_EQ(v.min_p95, 0.9);
  EXPECT_DOUBLE_EQ(v.max_p95, 1.3);
  for (bool stalled : v.baseline_stalled) EXPECT_FALSE(stalled);
}

TEST(TailRounds, ARoundWhoseBaselineStalledIsShownAndNotJudged) {
  // Four rounds where the subject is 1.5x its baseline; in a fifth the host stalled the baseline
  // (p99 40 against a usual 2) and the subject alike, which would read as 0.1x: a round that
  // makes the subject look good for the wrong reason.
  std::vector<RoundTails> rounds(4, RoundTails{1.5, 3.0, 1.0, 2.0});
  rounds.push_back({2.0, 4.0, 1.5, 40.0});
  const TailVerdict v = judge_tails(rounds);
  ASSERT_EQ(v.baseline_stalled.size(), 5u);
  EXPECT_TRUE(v.baseline_stalled[4]);
  EXPECT_FALSE(v.baseline_stalled[0]);
  EXPECT_DOUBLE_EQ(v.ratio_p99[4], 0.1) << "the stalled round's ratio is still shown";
  EXPECT_EQ(v.judged_rounds, 4u);
  EXPECT_DOUBLE_EQ(v.median_p99, 1.5);
  EXPECT_DOUBLE_EQ(v.min_p99, 1.5) << "the stalled round's 0.1 is not in the spread";
  // Just within the factor is no stall.
  rounds[4].baseline_p99 = kBaselineStallFactor * 2.0;
  EXPECT_FALSE(judge_tails(rounds).baseline_stalled[4]);
}

TEST(TailRounds, ARoundWithoutBaselineSamplesIsNotJudged) {
  const TailVerdict v = judge_tails({round_tails({1, 2, 3}, {}), round_tails({1, 2, 3}, {1, 2, 3})});
  EXPECT_EQ(v.judged_rounds, 1u);
  EXPECT_DOUBLE_EQ(v.ratio_p99[0], 0.0);
  EXPECT_DOUBLE_EQ(v.median_p99, 1.0);
  EXPECT_EQ(judge_tails({}).judged_rounds, 0u);
}

}  // namespace
}  // namespace hubrt::bench
