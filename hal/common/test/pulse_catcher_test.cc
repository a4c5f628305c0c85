#include "hubrt/hal/common/pulse_catcher.h"

#include <gtest/gtest.h>

namespace hubrt::hal {
namespace {

TEST(PulseCatcher, FirstReadReportsTheCurrentLevel) {
  PulseCatcher catcher;
  EXPECT_FALSE(catcher.reported().has_value());
  EXPECT_TRUE(catcher.report(true, true));
  EXPECT_EQ(catcher.reported(), true);
}

TEST(PulseCatcher, ALevelChangeIsReportedAtOnce) {
  PulseCatcher catcher;
  EXPECT_FALSE(catcher.report(false, false));
  EXPECT_TRUE(catcher.report(true, true));
  EXPECT_FALSE(catcher.report(false, true));
}

TEST(PulseCatcher, APulseBetweenTwoReadsIsReportedForExactlyOneRead) {
  PulseCatcher catcher;
  EXPECT_FALSE(catcher.report(false, false));
  EXPECT_TRUE(catcher.report(false, true));    // went high and back low since the last read
  EXPECT_FALSE(catcher.report(false, false));  // the read after shows the real level
  EXPECT_FALSE(catcher.report(false, false));
}

TEST(PulseCatcher, ALowGoingPulseIsCaughtToo) {
  PulseCatcher catcher;
  EXPECT_TRUE(catcher.report(true, false));
  EXPECT_FALSE(catcher.report(true, true));
  EXPECT_TRUE(catcher.report(true, false));
}

TEST(PulseCatcher, WithoutEdgesTheLevelIsReportedAsItIs) {
  PulseCatcher catcher;
  for (const bool level : {false, false, true, true, false}) EXPECT_EQ(catcher.report(level, false), level);
}

}  // namespace
}  // namespace hubrt::hal
