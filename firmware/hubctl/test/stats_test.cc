#include "stats.h"

#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

TEST(Summarize, NearestRankPercentiles) {
  std::vector<double> values;
  for (int i = 100; i >= 1; --i) values.push_back(i);
  const Summary s = summarize(values);
  EXPECT_EQ(s.count, 100u);
  EXPECT_EQ(s.min, 1);
  EXPECT_EQ(s.p50, 50);
  EXPECT_EQ(s.p90, 90);
  EXPECT_EQ(s.p95, 95);
  EXPECT_EQ(s.p99, 99);
  EXPECT_EQ(s.max, 100);
  EXPECT_DOUBLE_EQ(s.mean, 50.5);
}

// 60 samples (a round of the tails bench, bench/programs/tails.cc): p99 is the largest
// (rank ceil(59.4) = 60), p95 the 57th.
TEST(Summarize, NearestRankOfSixty) {
  std::vector<double> values;
  for (int i = 1; i <= 60; ++i) values.push_back(i);
  const Summary s = summarize(values);
  EXPECT_EQ(s.p95, 57);
  EXPECT_EQ(s.p99, 60);
}

TEST(Summarize, EmptyAndSingle) {
  EXPECT_EQ(summarize({}).count, 0u);
  EXPECT_EQ(summarize({}).p95, 0);
  const Summary one = summarize({7.5});
  EXPECT_EQ(one.p50, 7.5);
  EXPECT_EQ(one.p95, 7.5);
  EXPECT_EQ(one.p99, 7.5);
}

}  // namespace
}  // namespace hubrt::hubctl
