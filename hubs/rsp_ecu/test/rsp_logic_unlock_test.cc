// The tool-changer logic (RspLogicTest, rsp_test_support.h): how it starts, the tool-ID lines it
// decodes, and the unlock interlock both ways: the changer opens only while the Dock ECU's fresh
// State reports the tool on the changer home, and closes as soon as that stops being so.
#include <gtest/gtest.h>

#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::command;
using testing::OwnedCommand;
using testing::RspLogicTest;

// --- Start-up and decoding -------------------------------------------------------------------------

TEST_F(RspLogicTest, StartsLockedWithTheGripperAsTheBoardOpensIt) {
  RspLogic logic = make_logic();
  hub_msgs::RspState state = cycle(logic, nullptr);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(gripper_valve_energised()) << "host-sim.yaml: the gripper line opens closed (initial: true)";
  EXPECT_EQ(state.lock(), "closing") << "until a full stroke has passed the lock may still be closing";
  EXPECT_FALSE(state.locked());
  EXPECT_TRUE(state.safe_state());
  EXPECT_EQ(state.gripper(), "grab");

  state = run_for(logic, milliseconds(200), nullptr);
  EXPECT_EQ(state.tool(), "smart_tool") << "host-sim.yaml: the robot starts holding the smart tool";
  EXPECT_EQ(state.lock(), "closed");
  EXPECT_TRUE(state.locked());
  EXPECT_TRUE(state.pressure_ok());
  EXPECT_EQ(state.gripper_confirm(), "connected");
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_NE(std::string_view(state.unlock_blocked()).find("no Dock ECU State received yet"),
            std::string_view::npos)
      << state.unlock_blocked();
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

TEST_F(RspLogicTest, DecodesTheToolIdLinesAndReportsAnUndefinedOne) {
  RspLogic logic = make_logic();
  for (const std::string_view tool : {"ladder_frame_tool", "filter_tool", "none", "smart_tool"}) {
    tool_on_changer(tool);
    const hub_msgs::RspState state = run_for(logic, milliseconds(50), nullptr);  // past the 20 ms debounce
    EXPECT_EQ(state.tool(), tool);
  }
  hub_msgs::RspState state = run_for(logic, milliseconds(200), nullptr);
  EXPECT_TRUE(state.locked());
  tool_on_changer("none");
  state = run_for(logic, milliseconds(50), nullptr);
  EXPECT_FALSE(state.locked()) << "locked means locked onto a tool";

  tool_on_changer("smart_tool");
  set_input("rsp.tool_id.filter_tool", true);
  state = run_for(logic, milliseconds(50), nullptr);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(state.locked());
  EXPECT_TRUE(errors_.contains("tool id undefined: 2 tool-ID lines set at once (smart_tool, filter_tool)"))
      << errors_.at(0);
}

// --- The unlock interlock, both ways --------------------------------------------------------------

TEST_F(RspLogicTest, UnlockOpensTheChangerWhenTheDockReportsThatToolHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_TRUE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "");
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "opening");
  EXPECT_FALSE(state.locked());
  EXPECT_FALSE(state.safe_state());
  state = run_for(logic, milliseconds(200), &unlock);
  EXPECT_EQ(state.lock(), "open");
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);

  // The robot moves away: the tool stays in the dock, the ID lines go quiet, the changer stays open.
  tool_on_changer("none");
  state = run_for(logic, milliseconds(50), &unlock);
  EXPECT_EQ(state.tool(), "none");
  EXPECT_TRUE(lock_valve_energised());

  OwnedCommand lock = command("lock");
  state = cycle(logic, &lock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "closing");
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenTheToolIsNotHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, false);  // the smart tool is on the robot, not in its slot
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(500), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(fake_->history("rsp.lock_valve").empty() || !fake_->history("rsp.lock_valve").back().active);
  for (const auto& change : fake_->history("rsp.lock_valve")) EXPECT_FALSE(change.active) << "never opened";
  EXPECT_TRUE(state.locked());
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "the Dock ECU does not report smart_tool home (slot 'smart_tool' empty)");
  ASSERT_EQ(errors_.size(), 1u);
  EXPECT_EQ(errors_.at(0),
            "unlock refused: the Dock ECU does not report smart_tool home (slot 'smart_tool' empty); lock "
            "kept closed");
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenOnlyAnotherToolIsHome) {
  RspLogic logic = make_logic();
  tool_on_changer("filter_tool");
  dock_reports(true, false, true);  // ladder-frame and smart tools home, the filter tool is not
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(300), &unlock);
  EXPECT_EQ(state.tool(), "filter_tool");
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("filter_tool home (slot 'filter_tool' empty)"));
}

TEST_F(RspLogicTest, UnlockIsRefusedWhenTheDockStateWasNeverReceived) {
  RspLogic logic = make_logic();
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(
      errors_.contains("unlock refused: cannot confirm smart_tool is home: no Dock ECU State received yet "
                       "(/dock_ecu/dock/state); lock kept closed"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, AnOpenChangerClosesTheCycleTheDockStateGoesStale) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  dock_silent();
  run_for(logic, milliseconds(500), &unlock);
  EXPECT_TRUE(lock_valve_energised()) << "500 ms without a Dock State is still within its timeout";
  clock_.advance(kCycle);
  const hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "lost the moment it is older than the timeout";
  EXPECT_EQ(state.lock(), "closing");
  EXPECT_TRUE(errors_.contains("Dock ECU State older than 0.50 s (/dock_ecu/dock/state)")) << errors_.at(0);

  dock_reports(true, true, true);
  cycle(logic, &unlock);
  EXPECT_TRUE(lock_valve_energised()) << "the command in force acts again once the dock confirms";
}

TEST_F(RspLogicTest, AnOpenChangerClosesWhenTheDockNoLongerReportsTheToolHome) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(100), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  dock_reports(true, true, false);
  cycle(logic, &unlock);
  EXPECT_FALSE(lock_valve_energised());
}

TEST_F(RspLogicTest, AnUndefinedToolIdRefusesUnlockEvenWithEverySlotOccupied) {
  RspLogic logic = make_logic();
  tool_on_changer("smart_tool");
  set_input("rsp.tool_id.ladder_frame_tool", true);
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(300), &unlock);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("unlock refused: tool id undefined"));
}

TEST_F(RspLogicTest, AnUnreadableToolIdLineRefusesUnlock) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  auto wiring = fake_->wiring("rsp.tool_id.ladder_frame_tool");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspState state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_EQ(state.tool(), "undefined") << "a line that cannot be read might be the tool that is there";
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_TRUE(errors_.contains("input rsp.tool_id.ladder_frame_tool failed to read: i/o error"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, WithNoToolTheChangerOpensOnlyWhileTheDockIsAlive) {
  RspLogic logic = make_logic();
  tool_on_changer("none");
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "no Dock State: not allowed, even with nothing to drop";
  dock_reports(false, false, false);
  cycle(logic, &unlock);
  EXPECT_TRUE(lock_valve_energised());
}

TEST_F(RspLogicTest, ValidateRejectsAnUnlockTheInterlockDoesNotAllow) {
  RspLogic logic = make_logic();
  OwnedCommand unlock = command("unlock");
  const hub_msgs::RspCommandView wire = unlock.view();
  runtime::Problem problem;
  EXPECT_FALSE(logic.validate(wire, problem)) << "nothing evaluated yet: not allowed";
  dock_reports(true, true, false);
  run_for(logic, milliseconds(50), nullptr);
  EXPECT_FALSE(logic.validate(wire, problem));
  EXPECT_EQ(problem.view(),
            "unlock refused: the Dock ECU does not report smart_tool home (slot 'smart_tool' empty); lock "
            "kept closed");
  dock_reports(true, true, true);
  cycle(logic, nullptr);
  EXPECT_TRUE(logic.validate(wire, problem));
  OwnedCommand lock = command("lock");
  dock_silent();
  clock_.advance(milliseconds(600));
  cycle(logic, nullptr);
  EXPECT_TRUE(logic.validate(lock.view(), problem)) << "locking is always allowed";
}

TEST_F(RspLogicTest, ValidateRejectsAnUnknownGripperState) {
  RspLogic logic = make_logic();
  runtime::Problem problem;
  for (const std::string_view good : {"grab", "release", "keep", ""}) {
    OwnedCommand c = command("lock", good);
    EXPECT_TRUE(logic.validate(c.view(), problem)) << good;
  }
  OwnedCommand bad = command("lock", "open");
  EXPECT_FALSE(logic.validate(bad.view(), problem));
  EXPECT_EQ(problem.view(), "unknown gripper state 'open' (expected grab, release, keep, or empty for keep)");
  OwnedCommand shouting = command("reset", "GRAB");
  EXPECT_FALSE(logic.validate(shouting.view(), problem)) << "exact strings only";
}

}  // namespace
}  // namespace hubrt::rsp_ecu
