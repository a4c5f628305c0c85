#include "hubrt/base/time.h"

#include <gtest/gtest.h>

namespace hubrt {
namespace {

using std::chrono::milliseconds;

TEST(ManualClock, MovesOnlyWhenTold) {
  ManualClock clock;
  const Instant a = clock.now();
  EXPECT_EQ(clock.now().mono, a.mono);
  clock.advance(milliseconds(250));
  const Instant b = clock.now();
  EXPECT_EQ(b.mono - a.mono, milliseconds(250));
  EXPECT_EQ(b.wall.ns_since_epoch - a.wall.ns_since_epoch, 250'000'000);
  EXPECT_GT(a.mono.time_since_epoch(), Duration::zero());
}

TEST(SystemClock, IsMonotonic) {
  SystemClock clock;
  const Instant a = clock.now();
  const Instant b = clock.now();
  EXPECT_LE(a.mono, b.mono);
  EXPECT_GT(a.wall.ns_since_epoch, 1'600'000'000LL * 1'000'000'000);
}

}  // namespace
}  // namespace hubrt
