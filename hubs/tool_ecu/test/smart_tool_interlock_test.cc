// The smart tool node's logic on the fake backend (the simulated controller on a virtual CAN bus,
// fake GPIO) with a manual clock (SmartToolLogicTest, smart_tool_test_support.h): every interlock
// both ways (the robot's grip from the RSP ECU's State, the arm position, torque reached, inhibit,
// the summary alarm) and the manual buttons, which work only while the robot does not hold the tool.
#include <gtest/gtest.h>

#include "smart_tool_logic.h"
#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

// --- interlocks, both ways ---------------------------------------------------------------------

TEST_F(SmartToolLogicTest, TheToolRunsOnlyWhileTheRobotHoldsIt) {
  make_ready();
  set_tool_on_robot("none");
  const Order bolt1 = tighten(1);
  cycles(bolt1, 10);
  EXPECT_EQ(output(), "idle");
  EXPECT_FALSE(tool_->snapshot().running);
  EXPECT_EQ(blocked_by(), "the robot does not hold the smart tool (RSP ECU reports tool 'none')");
  EXPECT_FALSE(state_.robot_holds_tool());
  set_tool_on_robot("filter_tool");
  cycles(bolt1, 3);
  EXPECT_EQ(output(), "idle");
  set_tool_on_robot("smart_tool");
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  EXPECT_TRUE(state_.robot_holds_tool());
  EXPECT_EQ(blocked_by(), "");
  // Letting go of the tool mid-run stops it: the tightening ends NOK and is not repeated.
  set_tool_on_robot("none");
  cycle(&bolt1);
  EXPECT_EQ(output(), "idle");
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return state_.last_result().run_id() == 1; }));
  EXPECT_FALSE(state_.last_result().ok());
  set_tool_on_robot("smart_tool");
  cycles(bolt1, 10);
  EXPECT_EQ(tool_->snapshot().run_counter, 1);
}

TEST_F(SmartToolLogicTest, ALostRspStateCountsAsNotAllowed) {
  make_ready();
  rsp_alive_ = false;
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; })) << "fresh for another 500 ms";
  cycles(bolt1, 10);  // 500 ms later: lost
  EXPECT_EQ(output(), "idle");
  EXPECT_FALSE(state_.robot_holds_tool());
  EXPECT_EQ(blocked_by().rfind(
                "robot's grip on the tool unknown: input 'rsp' (/rsp_ecu/rsp/state): no State for", 0),
            0u)
      << blocked_by();
  EXPECT_NE(errors().find("robot state lost: input 'rsp' (/rsp_ecu/rsp/state): no State for"),
            std::string::npos)
      << errors();
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return state_.last_result().run_id() == 1; }));
  EXPECT_FALSE(state_.last_result().ok());

  rsp_alive_ = true;
  const Order bolt2 = tighten(2);
  ASSERT_TRUE(tighten_to_the_end(bolt2));
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(SmartToolLogicTest, ANeverReceivedRspStateCountsAsNotAllowed) {
  hub_api::RemoteState<hub_msgs::RspStateView> silent{"rsp", "/rsp_ecu/rsp/state", milliseconds(500),
                                                      hub_msgs_msg_dds__RspState__desc, 0};
  logic_.reset();  // its lines and bus go first: a line is opened by one owner at a time
  auto logic = make_smart_tool_logic(settings_, board_, *fake_, std::make_unique<RspToolHolder>(silent),
                                     clock_.now().mono);
  ASSERT_TRUE(logic);
  logic_.emplace(std::move(*logic));
  make_ready();
  const Order bolt1 = tighten(1);
  cycles(bolt1, 10);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(),
            "robot's grip on the tool unknown: input 'rsp' (/rsp_ecu/rsp/state): no State received yet");
  logic_.reset();  // before `silent` goes
}

TEST_F(SmartToolLogicTest, TheToolRunsOnlyWithTheArmInOperatingPosition) {
  make_ready();
  const Order bolt1 = tighten(1);
  struct Case {
    std::string_view signal;
    std::string_view expected;
  };
  for (const Case& c : {Case{"tool.arm.home", "home"}, Case{"tool.arm.pre_home", "pre_home"},
                        Case{"tool.arm.out_of_range", "out_of_range"}}) {
    fake_->input(c.signal)->set(true);
    cycles(bolt1, 3);
    EXPECT_EQ(std::string(state_.arm_position()), c.expected);
    EXPECT_EQ(output(), "idle") << c.signal;
    EXPECT_EQ(blocked_by(), std::string("arm not in operating position (") + std::string(c.expected) + ")");
    fake_->input(c.signal)->set(false);
  }
  fake_->input("tool.arm.home")->set(true);
  fake_->input("tool.arm.pre_home")->set(true);
  cycles(bolt1, 3);
  EXPECT_EQ(std::string(state_.arm_position()), "unclear");
  EXPECT_EQ(output(), "idle");
  fake_->input("tool.arm.home")->set(false);
  fake_->input("tool.arm.pre_home")->set(false);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  EXPECT_EQ(std::string(state_.arm_position()), "operating");
  EXPECT_EQ(tool_->snapshot().run_counter, 1) << "nothing ran while blocked";
}

TEST_F(SmartToolLogicTest, TorqueReachedStopsAForwardRunButNotALoosen) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  // A short pulse between two cycles is caught (catch_pulses) and stops the run.
  fake_->input("tool.torque_reached")->pulse(milliseconds(5));
  cycle(&bolt1);
  EXPECT_EQ(output(), "idle");
  EXPECT_TRUE(state_.torque_reached());
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return state_.last_result().run_id() == 1; }));
  // While the line is held, forward runs are refused and reverse is still possible.
  fake_->input("tool.torque_reached")->set(true);
  const Order bolt2 = tighten(2);
  cycles(bolt2, 5);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "torque reached");
  const Order loosen = action("loosen");
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; }));
  fake_->input("tool.torque_reached")->set(false);
  ASSERT_TRUE(tighten_to_the_end(bolt2));
  EXPECT_TRUE(state_.last_result().ok());
}

TEST_F(SmartToolLogicTest, InhibitForcesIdleAndDisablesTheButtons) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  const Order inhibit = action("inhibit");
  cycle(&inhibit);
  EXPECT_EQ(output(), "idle");
  ASSERT_TRUE(cycle_until(&inhibit, [&] { return !tool_->snapshot().running; }));
  set_tool_on_robot("none");  // the buttons would be allowed, but not under inhibit
  fake_->input("tool.button.forward")->set(true);
  cycles(inhibit, 5);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "manual buttons disabled: inhibit command");
  EXPECT_FALSE(tool_->snapshot().running);
}

TEST_F(SmartToolLogicTest, TheSummaryAlarmForcesIdleAndLatchesUntilReset) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  fake_->input("tool.summary_alarm")->set(true);
  cycles(bolt1, 1);
  cycles(bolt1, 1);  // past the 10 ms debounce
  EXPECT_EQ(output(), "idle");
  EXPECT_NE(errors().find("summary alarm input active; outputs idle"), std::string::npos) << errors();
  fake_->input("tool.summary_alarm")->set(false);
  cycles(bolt1, 3);
  EXPECT_NE(errors().find("summary alarm occurred; send reset to clear"), std::string::npos) << errors();
  const Order bolt2 = tighten(2);
  cycles(bolt2, 5);
  EXPECT_EQ(output(), "idle") << "latched";
  EXPECT_EQ(blocked_by(), "summary alarm (latched: send reset)");
  EXPECT_EQ(logic_->condition(), runtime::NodeCondition::kFault) << "the node's lifecycle: fault";
  reset_command();
  EXPECT_EQ(logic_->condition(), runtime::NodeCondition::kOk);
  EXPECT_TRUE(errors_.empty()) << errors();
  ASSERT_TRUE(tighten_to_the_end(bolt2));
  EXPECT_TRUE(state_.last_result().ok());
}

// --- the manual buttons ------------------------------------------------------------------------

TEST_F(SmartToolLogicTest, ManualButtonsWorkOnlyWhileTheRobotDoesNotHoldTheTool) {
  make_ready();
  const Order idle = action("idle");
  fake_->input("tool.button.forward")->set(true);
  cycles(idle, 5);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "manual buttons disabled: the robot holds the smart tool");
  EXPECT_TRUE(state_.button_forward());

  set_tool_on_robot("none");  // the robot left the tool floating: the operator uses it
  ASSERT_TRUE(cycle_until(&idle, [&] { return output() == "forward"; }));
  EXPECT_EQ(std::string(state_.activity()), "manual_forward");
  EXPECT_EQ(std::string(state_.selected_program()), "pipe_plate") << "the hub file's manual_program";
  fake_->input("tool.button.forward")->set(false);
  cycles(idle, 2);
  EXPECT_EQ(output(), "idle");
  ASSERT_TRUE(cycle_until(&idle, [&] { return !state_.last_result().program().empty(); }));
  EXPECT_EQ(state_.last_result().run_id(), 0u) << "manual runs have run_id 0";
  EXPECT_EQ(state_.last_result().program(), "pipe_plate");

  fake_->input("tool.button.reverse")->set(true);
  ASSERT_TRUE(cycle_until(&idle, [&] { return output() == "reverse"; }));
  EXPECT_EQ(std::string(state_.activity()), "manual_reverse");
  EXPECT_EQ(tool_->snapshot().direction, st::Direction::kReverse);
  // The robot takes the tool again: the buttons stop working at once.
  set_tool_on_robot("smart_tool");
  cycle(&idle);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "manual buttons disabled: the robot holds the smart tool");
}

TEST_F(SmartToolLogicTest, ManualButtonsDoNothingWhenTheRspStateIsLostOrNoCommandIsInForce) {
  make_ready();
  set_tool_on_robot("none");
  fake_->input("tool.button.reverse")->set(true);
  cycles(nullptr, 5);
  EXPECT_EQ(output(), "idle") << "no command in force: the safe state, buttons ignored";
  const Order idle = action("idle");
  ASSERT_TRUE(cycle_until(&idle, [&] { return output() == "reverse"; }));
  rsp_alive_ = false;
  cycles(idle, 11);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by().rfind("manual buttons disabled: robot's grip on the tool unknown", 0), 0u)
      << blocked_by();
  rsp_alive_ = true;
  fake_->input("tool.button.forward")->set(true);
  cycles(idle, 3);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "both manual buttons pressed");
}

}  // namespace
}  // namespace hubrt::tool_ecu
