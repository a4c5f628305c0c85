// The tool-changer logic (RspLogicTest, rsp_test_support.h) when something is wrong: a pressure
// drop, no command in force, a reset, leaving control, devices that are missing or fail, and a
// board that would open the lock on a fault: every safe state and the recovery after a reset.
#include <gtest/gtest.h>

#include "rsp_logic.h"
#include "rsp_test_support.h"

namespace hubrt::rsp_ecu {
namespace {

using std::chrono::milliseconds;
using testing::command;
using testing::OwnedCommand;
using testing::RspLogicTest;

// --- Pressure --------------------------------------------------------------------------------------

TEST_F(RspLogicTest, APressureDropMidOperationLatchesAndHoldsTheSafeStateUntilReset) {
  RspLogic logic = make_logic();
  tool_on_changer("ladder_frame_tool");
  dock_reports(true, true, false);
  OwnedCommand grab = command("lock", "grab");
  run_for(logic, milliseconds(300), &grab);
  // Mid-operation: the planner releases the ladder frame, and the air goes as the valve moves.
  OwnedCommand release = command("lock", "release");
  cycle(logic, &release);
  ASSERT_FALSE(gripper_valve_energised());
  fake_->pressure_supply("main_air")->drop();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), &release);  // past the switch's 50 ms debounce
  EXPECT_FALSE(state.pressure_ok());
  EXPECT_TRUE(state.pressure_known()) << "a switch that reads off is a known pressure loss";
  EXPECT_TRUE(state.safe_state());
  EXPECT_TRUE(
      errors_.contains("pressure failure: supply pressure lost (rsp.pressure_ok off) (latched: lock held "
                       "closed, gripper as it is; reset to clear)"))
      << errors_.at(0);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised()) << "gripper as it is";
  EXPECT_FALSE(errors_.contains("gripper failed")) << "a gripper without air is not a failed gripper";

  OwnedCommand grab_again = command("lock", "grab");
  run_for(logic, milliseconds(100), &grab_again);
  EXPECT_FALSE(gripper_valve_energised()) << "no command acts while the fault is latched";

  fake_->pressure_supply("main_air")->restore();
  state = run_for(logic, milliseconds(1000), &grab_again);
  EXPECT_TRUE(state.pressure_ok());
  EXPECT_TRUE(logic.fault_latched()) << "pressure back is not enough: latched until reset";

  logic.reset();
  OwnedCommand reset = command("reset");
  state = run_for(logic, milliseconds(100), &reset);
  EXPECT_FALSE(logic.fault_latched());
  EXPECT_TRUE(state.safe_state()) << "reset itself keeps the lock closed and the gripper as it is";
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);

  state = run_for(logic, milliseconds(300), &grab_again);
  EXPECT_TRUE(gripper_valve_energised()) << "a fresh command acts after the reset";
  EXPECT_FALSE(state.safe_state());
  EXPECT_EQ(state.gripper_confirm(), "connected");
}

TEST_F(RspLogicTest, APressureDropWhileOpenClosesTheLockAndAResetWithoutPressureLatchesAgain) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  fake_->pressure_supply("main_air")->drop();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_EQ(state.lock(), "closing") << "no air: the lock cannot move until pressure returns";
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_EQ(state.unlock_blocked(), "a pressure failure is latched; reset first");
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault);
  logic.reset();
  OwnedCommand reset = command("reset");
  cycle(logic, &reset);
  EXPECT_TRUE(logic.fault_latched()) << "the pressure is still gone";
  fake_->pressure_supply("main_air")->restore();
  // The stroke starts over once the switch shows pressure again (after its 50 ms debounce).
  state = run_for(logic, milliseconds(240), &reset);
  EXPECT_EQ(state.lock(), "closing");
  state = run_for(logic, milliseconds(20), &reset);
  EXPECT_EQ(state.lock(), "closed");
}

TEST_F(RspLogicTest, AnUnreadablePressureSwitchIsAPressureFailure) {
  auto wiring = fake_->wiring("rsp.pressure_ok");
  ASSERT_TRUE(wiring.is_ok());
  RspLogic logic = make_logic();
  hub_msgs::RspState state = run_for(logic, milliseconds(100), nullptr);  // past the switch's 50 ms debounce
  ASSERT_TRUE(state.pressure_ok());
  EXPECT_TRUE(state.pressure_known());

  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  clock_.advance(kCycle);
  state = cycle(logic, nullptr);
  EXPECT_FALSE(state.pressure_known()) << "the read failed: the pressure is unknown this very cycle";
  EXPECT_FALSE(state.pressure_ok()) << "not the last good reading";
  EXPECT_TRUE(errors_.contains("pressure failure: pressure switch rsp.pressure_ok cannot be read"))
      << errors_.at(0);

  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, false).is_ok());
  state = run_for(logic, milliseconds(100), nullptr);
  EXPECT_TRUE(state.pressure_known());
  EXPECT_TRUE(state.pressure_ok()) << "a good read brings the value back (the failure stays latched)";
  EXPECT_TRUE(logic.fault_latched());
}

// --- Safe states -----------------------------------------------------------------------------------

TEST_F(RspLogicTest, NoCommandInForceClosesTheLockAndKeepsTheGripperEitherWay) {
  for (const bool grab : {true, false}) {
    SCOPED_TRACE(grab ? "gripper closed" : "gripper open");
    SetUp();
    RspLogic logic = make_logic();
    dock_reports(true, true, true);
    OwnedCommand unlock = command("unlock", grab ? "grab" : "release");
    run_for(logic, milliseconds(300), &unlock);
    ASSERT_TRUE(lock_valve_energised());
    ASSERT_EQ(gripper_valve_energised(), grab);
    const hub_msgs::RspState state = cycle(logic, nullptr);  // the watchdog tripped
    EXPECT_FALSE(lock_valve_energised());
    EXPECT_EQ(gripper_valve_energised(), grab);
    EXPECT_TRUE(state.safe_state());
  }
}

TEST_F(RspLogicTest, AResetCommandClosesTheLockAndKeepsTheGripper) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock", "release");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  OwnedCommand reset = command("reset", "grab");
  const hub_msgs::RspState state = cycle(logic, &reset);
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised()) << "a reset moves nothing but the lock, whatever its gripper says";
  EXPECT_TRUE(state.safe_state());
}

TEST_F(RspLogicTest, EnterSafeStateClosesTheLockAndLeavesTheGripper) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock", "release");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  logic.enter_safe_state();
  EXPECT_FALSE(lock_valve_energised());
  EXPECT_FALSE(gripper_valve_energised());
  EXPECT_TRUE(logic.in_safe_state());
}

// --- Devices that fail -----------------------------------------------------------------------------

TEST_F(RspLogicTest, AMissingChipIsReportedEverythingStaysLockedAndItRecovers) {
  auto wiring = fake_->wiring("rsp.lock_valve");
  ASSERT_TRUE(wiring.is_ok());
  wiring.value().chip->vanish();
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  hub_msgs::RspState state = cycle(logic, &unlock);
  EXPECT_EQ(state.tool(), "undefined");
  EXPECT_FALSE(state.unlock_allowed());
  EXPECT_FALSE(state.pressure_ok());
  EXPECT_FALSE(state.pressure_known()) << "the chip is gone";
  EXPECT_TRUE(errors_.contains("output rsp.lock_valve not available:")) << errors_.at(0);
  EXPECT_TRUE(errors_.contains("input rsp.tool_id.smart_tool not available:"));
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kFault)
      << "the unreadable pressure switch latched a pressure failure: it outranks the missing devices";

  wiring.value().chip->reappear();
  clock_.advance(std::chrono::seconds(3));  // past the retry interval
  run_for(logic, milliseconds(100), &unlock);
  EXPECT_FALSE(lock_valve_energised()) << "the pressure failure seen meanwhile is latched";
  logic.reset();
  OwnedCommand reset = command("reset");
  run_for(logic, milliseconds(100), &reset);
  state = run_for(logic, milliseconds(100), &unlock);
  EXPECT_TRUE(lock_valve_energised());
  EXPECT_TRUE(errors_.empty()) << errors_.at(0);
  EXPECT_EQ(logic.condition(), runtime::NodeCondition::kOk);
}

TEST_F(RspLogicTest, AFailedWriteIsReported) {
  RspLogic logic = make_logic();
  auto wiring = fake_->wiring("rsp.gripper_valve");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_writes(wiring.value().line, true).is_ok());
  OwnedCommand release = command("lock", "release");
  cycle(logic, &release);
  EXPECT_TRUE(errors_.contains("output rsp.gripper_valve failed to write: i/o error")) << errors_.at(0);
}

TEST_F(RspLogicTest, ABoardThatWouldOpenTheLockOnFaultsIsRefused) {
  for (hal::BoardOutput& output : board_.outputs) {
    if (output.config.signal == "rsp.lock_valve") output.config.safe = true;
  }
  auto logic = testing::make_rsp_logic(settings_, board_, *fake_, dock_.input(), clock_.now().mono);
  ASSERT_FALSE(logic);
  EXPECT_NE(
      logic.error().message.find("drives the lock valve 'rsp.lock_valve' active (= changer open) on faults"),
      std::string::npos)
      << logic.error().message;
}

}  // namespace
}  // namespace hubrt::rsp_ecu
