// The pure parts of the tool-changer node: tool-ID decoding, the unlock interlock, the lock's
// position from its valve, and the gripper confirm supervision.
#include <gtest/gtest.h>

#include "gripper_monitor.h"
#include "lock_position.h"
#include "rsp_test_support.h"
#include "tool_id.h"
#include "unlock_interlock.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::dock_slots;
using testing::DockFeed;

constexpr ToolLineReading kOff{true, false};
constexpr ToolLineReading kOn{true, true};
constexpr ToolLineReading kUnreadable{false, false};

TEST(ToolIdDecoding, NoLineIsNoToolOneLineIsThatToolMoreAreUndefined) {
  EXPECT_EQ(decode_tool_id(std::array{kOff, kOff, kOff}).kind, ToolId::Kind::kNone);
  for (std::size_t i = 0; i < 3; ++i) {
    std::array lines{kOff, kOff, kOff};
    lines[i] = kOn;
    const ToolId id = decode_tool_id(lines);
    EXPECT_EQ(id.kind, ToolId::Kind::kOne);
    EXPECT_EQ(id.index, i);
  }
  EXPECT_EQ(decode_tool_id(std::array{kOn, kOn, kOff}).kind, ToolId::Kind::kUndefined);
  EXPECT_EQ(decode_tool_id(std::array{kOn, kOn, kOn}).kind, ToolId::Kind::kUndefined);
}

TEST(ToolIdDecoding, AnUnreadableLineIsUndefinedNeverNone) {
  EXPECT_EQ(decode_tool_id(std::array{kOff, kUnreadable, kOff}).kind, ToolId::Kind::kUndefined);
  EXPECT_EQ(decode_tool_id(std::array{kOn, kOff, kUnreadable}).kind, ToolId::Kind::kUndefined);
}

// The interlock table, row by row.
class UnlockInterlock : public ::testing::Test {
 protected:
  bool permitted(ToolId tool, std::string_view name) {
    return unlock_permitted(tool, name, feed_.input(), clock_.now().mono, why_);
  }

  static constexpr ToolId kSmart{ToolId::Kind::kOne, 2};
  static constexpr ToolId kNone{ToolId::Kind::kNone, 0};
  static constexpr ToolId kUndefined{ToolId::Kind::kUndefined, 0};
  ManualClock clock_;
  DockFeed feed_{milliseconds(500)};
  runtime::Problem why_;
};

TEST_F(UnlockInterlock, AllowedOnlyWithAFreshReportOfThatToolHome) {
  feed_.arrive(dock_slots(true, true, true), clock_.now().mono);
  EXPECT_TRUE(permitted(kSmart, "smart_tool"));
  EXPECT_TRUE(why_.empty());
  clock_.advance(milliseconds(500));
  EXPECT_TRUE(permitted(kSmart, "smart_tool")) << "exactly at the timeout the State still counts";
}

TEST_F(UnlockInterlock, RefusedWhenTheToolIsNotHome) {
  feed_.arrive(dock_slots(true, true, false), clock_.now().mono);
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
  EXPECT_EQ(why_.view(), "the Dock ECU does not report smart_tool home (slot 'smart_tool' empty)");
}

TEST_F(UnlockInterlock, RefusedWhenAnotherToolIsHomeButNotThisOne) {
  feed_.arrive({{"ladder_frame_tool", true}, {"filter_tool", true}, {"smart_tool", false}},
               clock_.now().mono);
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
}

TEST_F(UnlockInterlock, RefusedWhenTheDockListsNoSlotForTheTool) {
  feed_.arrive({{"ladder_frame_tool", true}, {"filter_tool", true}}, clock_.now().mono);
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
  EXPECT_EQ(why_.view(), "the Dock ECU State lists no slot 'smart_tool': cannot confirm smart_tool is home");
}

TEST_F(UnlockInterlock, RefusedWhenTheDockStateWasNeverReceived) {
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
  EXPECT_EQ(why_.view(),
            "cannot confirm smart_tool is home: no Dock ECU State received yet (/dock_ecu/dock/state)");
  EXPECT_FALSE(permitted(kNone, "none")) << "with no tool on the changer, loss still counts as not allowed";
  EXPECT_EQ(why_.view(), "no Dock ECU State received yet (/dock_ecu/dock/state)");
}

TEST_F(UnlockInterlock, RefusedWhenTheDockStateIsStale) {
  feed_.arrive(dock_slots(true, true, true), clock_.now().mono);
  clock_.advance(milliseconds(501));
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
  EXPECT_EQ(why_.view(),
            "cannot confirm smart_tool is home: Dock ECU State older than 0.50 s (/dock_ecu/dock/state)");
  const std::string first(why_.view());
  clock_.advance(milliseconds(300));
  EXPECT_FALSE(permitted(kSmart, "smart_tool"));
  EXPECT_EQ(why_.view(), first) << "the same reason reads the same later (the log is not flooded)";
  feed_.arrive(dock_slots(true, true, true), clock_.now().mono);
  EXPECT_TRUE(permitted(kSmart, "smart_tool")) << "a fresh State allows it again";
}

TEST_F(UnlockInterlock, RefusedForAnUndefinedToolWhateverTheDockSays) {
  feed_.arrive(dock_slots(true, true, true), clock_.now().mono);
  EXPECT_FALSE(permitted(kUndefined, "undefined"));
  EXPECT_EQ(why_.view(), "tool id undefined: cannot tell which tool the changer would release");
}

TEST_F(UnlockInterlock, WithNoToolOnTheChangerAFreshDockStateAllowsOpening) {
  // Nothing can drop, and the changer has to be open to take a tool from the dock.
  feed_.arrive(dock_slots(false, false, false), clock_.now().mono);
  EXPECT_TRUE(permitted(kNone, "none"));
}

TEST(LockPositionTest, ClosedOnlyAfterAFullStrokeWithPressure) {
  ManualClock clock;
  LockPosition lock(milliseconds(200), clock.now().mono);
  EXPECT_EQ(lock.name(), "closing") << "at start the lock may still be closing";
  EXPECT_FALSE(lock.closed());
  clock.advance(milliseconds(199));
  lock.advance(clock.now().mono);
  EXPECT_FALSE(lock.closed());
  clock.advance(milliseconds(1));
  lock.advance(clock.now().mono);
  EXPECT_TRUE(lock.closed());
  EXPECT_EQ(lock.name(), "closed");

  lock.drive(true, clock.now().mono);
  EXPECT_EQ(lock.name(), "opening");
  EXPECT_FALSE(lock.closed()) << "closed the moment the valve opens it no longer holds";
  clock.advance(milliseconds(200));
  lock.advance(clock.now().mono);
  EXPECT_EQ(lock.name(), "open");

  lock.drive(false, clock.now().mono);
  clock.advance(milliseconds(100));
  lock.pressure(false, clock.now().mono);
  clock.advance(milliseconds(500));
  lock.advance(clock.now().mono);
  EXPECT_EQ(lock.name(), "closing") << "without pressure the piston stays where it is";
  lock.pressure(true, clock.now().mono);
  clock.advance(milliseconds(150));
  lock.advance(clock.now().mono);
  EXPECT_EQ(lock.name(), "closing") << "the stroke starts over when pressure returns";
  clock.advance(milliseconds(50));
  lock.advance(clock.now().mono);
  EXPECT_EQ(lock.name(), "closed");
}

class GripperMonitorTest : public ::testing::Test {
 protected:
  void lines(bool a, bool b) { monitor_.observe(true, a, true, b, clock_.now().mono); }
  void supervise(bool grab, bool active = true) {
    monitor_.valve(grab, clock_.now().mono);
    monitor_.supervise(active, clock_.now().mono);
  }

  ManualClock clock_;
  GripperMonitor monitor_{milliseconds(500)};
};

TEST_F(GripperMonitorTest, ConfirmStatesFromTheTwoLines) {
  lines(false, false);
  EXPECT_EQ(monitor_.confirm_name(), "not_connected");
  lines(true, true);
  EXPECT_EQ(monitor_.confirm_name(), "connected");
  lines(true, false);
  EXPECT_EQ(monitor_.confirm_name(), "moving");
  clock_.advance(milliseconds(500));
  lines(true, false);
  EXPECT_EQ(monitor_.confirm_name(), "moving") << "disagreeing for the confirm time is still allowed";
  clock_.advance(milliseconds(1));
  lines(true, false);
  EXPECT_EQ(monitor_.confirm_name(), "failed");
  monitor_.observe(true, true, false, false, clock_.now().mono);
  EXPECT_EQ(monitor_.confirm_name(), "unknown") << "an unreadable line confirms nothing";
}

TEST_F(GripperMonitorTest, AGripThatDoesNotArriveWithinTheConfirmTimeIsLatched) {
  lines(false, false);
  supervise(false);
  supervise(true);  // the valve closes the gripper now
  clock_.advance(milliseconds(500));
  lines(false, false);
  supervise(true);
  EXPECT_FALSE(monitor_.faulted()) << "the valve's actuation time is not a failure";
  clock_.advance(milliseconds(1));
  lines(false, false);
  supervise(true);
  ASSERT_TRUE(monitor_.faulted());
  EXPECT_EQ(monitor_.fault(),
            "gripper failed to grab: confirm lines still show not_connected after 501 ms (limit 500 ms)");
  lines(true, true);
  supervise(true);
  EXPECT_TRUE(monitor_.faulted()) << "latched until reset";
  monitor_.reset();
  supervise(true);
  EXPECT_FALSE(monitor_.faulted());
}

TEST_F(GripperMonitorTest, AReleaseThatDoesNotHappenIsLatchedToo) {
  lines(true, true);
  supervise(true);
  supervise(false);
  clock_.advance(milliseconds(501));
  lines(true, true);
  supervise(false);
  EXPECT_EQ(monitor_.fault(),
            "gripper failed to release: confirm lines still show connected after 501 ms (limit 500 ms)");
}

TEST_F(GripperMonitorTest, DisagreeingLinesAreLatchedOnceFailed) {
  lines(true, true);
  supervise(true);
  clock_.advance(milliseconds(1000));
  lines(true, false);
  supervise(true);
  EXPECT_FALSE(monitor_.faulted())
      << "long after the valve moved, disagreeing lines still get the confirm time";
  clock_.advance(milliseconds(500));
  lines(true, false);
  supervise(true);
  EXPECT_FALSE(monitor_.faulted());
  clock_.advance(milliseconds(1));
  lines(true, false);
  supervise(true);
  EXPECT_EQ(monitor_.fault(), "gripper failed: confirm lines disagree (A on, B off) for more than 500 ms");
}

TEST_F(GripperMonitorTest, NothingIsSupervisedWhileInactiveAndTheClockStartsWhenItBecomesActive) {
  lines(false, false);
  supervise(true, false);
  clock_.advance(milliseconds(5000));
  supervise(true, false);
  EXPECT_FALSE(monitor_.faulted()) << "inactive: no gripper tool on the changer, or no pressure";
  supervise(true, true);
  clock_.advance(milliseconds(400));
  supervise(true, true);
  EXPECT_FALSE(monitor_.faulted()) << "the gripper gets the full confirm time once active";
  clock_.advance(milliseconds(101));
  supervise(true, true);
  EXPECT_TRUE(monitor_.faulted());
}

}  // namespace
}  // namespace hubrt::rsp_ecu
