// The tool-changer logic (RspLogicTest, rsp_test_support.h): the ladder-frame gripper following
// its command, and a grip its confirm lines do not confirm latched as a fault.
#include <gtest/gtest.h>

#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::command;
using testing::OwnedCommand;
using testing::RspLogicTest;

// --- The gripper -----------------------------------------------------------------------------------

TEST_F(RspLogicTest, TheGripperFollowsItsCommandAndKeepLeavesItAsItIs) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  OwnedCommand release = command("lock", "release");
  hub_msgs::RspState state = run_for(logic, milliseconds(300), &release);
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_EQ(state.gripper(), "release");
  EXPECT_EQ(state.gripper_confirm(), "not_connected");
  OwnedCommand keep = command("lock", "keep");
  run_for(logic, milliseconds(100), &keep);
  EXPECT_FALSE(gripper_valve_energised());
  OwnedCommand grab = command("lock", "grab");
  state = cycle(logic, &grab);
  EXPECT_TRUE(gripper_valve_energised());
  EXPECT_EQ(state.gripper_confirm(), "not_connected") << "the gripper takes 150 ms to close";
  state = run_for(logic, milliseconds(300), &grab);
  EXPECT_EQ(state.gripper_confirm(), "connected");
  OwnedCommand empty = command("lock", "");
  run_for(logic, milliseconds(100), &empty);
  EXPECT_TRUE(gripper_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

TEST_F(RspLogicTest, AGripThatFailsIsLatchedAfterTheConfirmDelayAndHoldsTheSafeState) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  dock_reports(true, true, false);
  OwnedCommand release = command("lock", "release");
  run_for(logic, milliseconds(300), &release);
  fake_->valve("rsp.gripper_valve")->stick(true);  // the gripper jams open
  OwnedCommand grab = command("lock", "grab");
  hub_msgs::RspState state = run_for(logic, milliseconds(490), &grab);
  EXPECT_FALSE(logic.fault_latched()) << "within the 500 ms confirm delay nothing is called failed";
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  state = run_for(logic, milliseconds(20), &grab);
  ASSERT_TRUE(logic.fault_latched());
  EXPECT_TRUE(errors_.contains("gripper failed to grab: confirm lines still show not_connected after"))
      << errors_.at(0);
  EXPECT_TRUE(errors_.contains("latched: lock held closed, gripper as it is; reset to clear"));
  EXPECT_TRUE(state.safe_state());
  EXPECT_TRUE(gripper_valve_energised()) << "the gripper stays as it is";

  // While latched, no gripper or lock command acts.
  OwnedCommand release_again = command("lock", "release");
  run_for(logic, milliseconds(100), &release_again);
  EXPECT_TRUE(gripper_valve_energised());
  dock_reports(true, true, true);
  tool_on_changer("ladder_frame_tool");
  OwnedCommand unlock = command("unlock");
  state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.unlock_blocked(), "a gripper failure is latched; reset first");
}

TEST_F(RspLogicTest, ConfirmLinesThatDisagreeAreLatchedAsAFailedGripper) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  OwnedCommand grab = command("lock", "grab");
  run_for(logic, milliseconds(300), &grab);
  fake_->valve("rsp.gripper_valve")->fail_confirm(1, false);  // sensor B drops out
  hub_msgs::RspState state = run_for(logic, milliseconds(400), &grab);
  EXPECT_EQ(state.gripper_confirm(), "moving");
  EXPECT_FALSE(logic.fault_latched());
  state = run_for(logic, milliseconds(200), &grab);
  EXPECT_EQ(state.gripper_confirm(), "failed");
  EXPECT_TRUE(errors_.contains("gripper failed: confirm lines disagree (A on, B off) for more than 500 ms"))
      << errors_.at(0);
}

TEST_F(RspLogicTest, TheGripperIsNotSupervisedWithoutItsTool) {
  RspLogic logic = make_logic();  // the smart tool is on the changer: it has no gripper
  fake_->valve("rsp.gripper_valve")->stick(true);
  OwnedCommand release = command("lock", "release");
  run_for(logic, milliseconds(2000), &release);
  EXPECT_FALSE(logic.fault_latched());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
}

}  // namespace
}  // namespace hubrt::rsp_ecu
