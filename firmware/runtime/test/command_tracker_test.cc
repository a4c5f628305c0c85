#include "hubrt/runtime/command_tracker.h"

#include <gtest/gtest.h>

namespace hubrt::runtime {
namespace {

using std::chrono::milliseconds;
using Arrival = CommandTracker::Arrival;
using Watchdog = CommandTracker::Watchdog;

class CommandTrackerTest : public ::testing::Test {
 protected:
  Time now() const { return clock_.now().mono; }
  ManualClock clock_;
  CommandTracker tracker_{milliseconds(500)};
};

TEST_F(CommandTrackerTest, NothingInForceBeforeTheFirstCommand) {
  EXPECT_FALSE(tracker_.has_echo());
  EXPECT_FALSE(tracker_.in_force());
  EXPECT_FALSE(tracker_.fresh());
  EXPECT_EQ(tracker_.t_plus(now()), 0.0);
  EXPECT_EQ(tracker_.check(now()), Watchdog::kQuiet);
}

TEST_F(CommandTrackerTest, TPlusCountsFromFirstArrivalAndRepeatsDoNotRestartIt) {
  EXPECT_EQ(tracker_.on_valid_command(now(), true, false), Arrival::kTookEffect);
  clock_.advance(milliseconds(100));
  EXPECT_EQ(tracker_.on_valid_command(now(), false, false), Arrival::kRepeat);
  clock_.advance(milliseconds(150));
  EXPECT_DOUBLE_EQ(tracker_.t_plus(now()), 0.25);
  EXPECT_TRUE(tracker_.fresh());
  EXPECT_EQ(tracker_.on_valid_command(now(), true, false), Arrival::kTookEffect);
  EXPECT_DOUBLE_EQ(tracker_.t_plus(now()), 0.0);
}

TEST_F(CommandTrackerTest, WatchdogTripsOnceAfterTheTimeoutNotAtIt) {
  tracker_.on_valid_command(now(), true, false);
  clock_.advance(milliseconds(500));
  EXPECT_EQ(tracker_.check(now()), Watchdog::kQuiet) << "exactly at the timeout is still fresh";
  EXPECT_TRUE(tracker_.fresh());
  clock_.advance(milliseconds(1));
  EXPECT_EQ(tracker_.check(now()), Watchdog::kTripped);
  EXPECT_FALSE(tracker_.fresh());
  EXPECT_FALSE(tracker_.in_force());
  EXPECT_TRUE(tracker_.has_echo()) << "the echo of the last command stays visible";
  EXPECT_EQ(tracker_.check(now()), Watchdog::kQuiet) << "trips once per loss";
}

TEST_F(CommandTrackerTest, RepeatsKeepTheWatchdogFed) {
  tracker_.on_valid_command(now(), true, false);
  for (int i = 0; i < 20; ++i) {
    clock_.advance(milliseconds(400));
    tracker_.on_valid_command(now(), false, false);
    EXPECT_EQ(tracker_.check(now()), Watchdog::kQuiet);
  }
  EXPECT_DOUBLE_EQ(tracker_.t_plus(now()), 8.0);
}

TEST_F(CommandTrackerTest, AfterATripOnlyANewArrivalActsAndItRestartsTPlus) {
  tracker_.on_valid_command(now(), true, false);
  clock_.advance(milliseconds(600));
  ASSERT_EQ(tracker_.check(now()), Watchdog::kTripped);
  clock_.advance(milliseconds(1000));
  EXPECT_FALSE(tracker_.in_force()) << "time passing alone never re-applies the old command";
  // The planner comes back with the same content: it is a new command and takes effect.
  EXPECT_EQ(tracker_.on_valid_command(now(), false, false), Arrival::kTookEffect);
  EXPECT_TRUE(tracker_.in_force());
  EXPECT_DOUBLE_EQ(tracker_.t_plus(now()), 0.0);
}

TEST_F(CommandTrackerTest, GotResetFollowsTheCommandInForce) {
  tracker_.on_valid_command(now(), true, true);
  EXPECT_TRUE(tracker_.got_reset());
  EXPECT_EQ(tracker_.on_valid_command(now(), false, true), Arrival::kRepeat);
  EXPECT_TRUE(tracker_.got_reset());
  tracker_.on_valid_command(now(), true, false);
  EXPECT_FALSE(tracker_.got_reset());
  tracker_.on_valid_command(now(), true, true);
  clock_.advance(milliseconds(501));
  tracker_.check(now());
  EXPECT_FALSE(tracker_.got_reset()) << "a reset that is no longer in force is not reported";
}

}  // namespace
}  // namespace hubrt::runtime
