// The smart tool node's logic on the fake backend (the simulated controller on a virtual CAN bus,
// fake GPIO) with a manual clock: tightenings and their identity, every interlock both ways, the
// manual buttons, every safe state, faults and recovery after reset.
#include "smart_tool_logic.h"

#include <gtest/gtest.h>

#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

// --- tightenings and their identity ------------------------------------------------------------

TEST_F(SmartToolLogicTest, ATighteningSelectsItsProgramRunsForwardAndReportsItsResult) {
  make_ready();
  const Order bolt7 = tighten(7);
  cycle(&bolt7);
  EXPECT_EQ(std::string(state_.activity()), "tightening");
  EXPECT_EQ(state_.active_run_id(), 7u);
  ASSERT_TRUE(cycle_until(&bolt7, [&] { return output() == "forward"; }));
  EXPECT_TRUE(line("tool.run_forward"));
  EXPECT_FALSE(line("tool.run_reverse"));
  EXPECT_EQ(std::string(state_.selected_program()), "ladder_frame_bolt");
  ASSERT_TRUE(tool_->snapshot().program.has_value());
  EXPECT_EQ(*tool_->snapshot().program, settings_.programs[0].program)
      << "the hub file's torque and angle window";
  EXPECT_TRUE(tool_->snapshot().running);

  ASSERT_TRUE(tighten_to_the_end(bolt7)) << errors();
  EXPECT_FALSE(line("tool.run_forward"));
  EXPECT_EQ(state_.active_run_id(), 0u);
  const hub_msgs::SmartToolResultView result = state_.last_result();
  EXPECT_TRUE(result.ok()) << result.nok_reasons();
  EXPECT_EQ(result.program(), "ladder_frame_bolt");
  EXPECT_NEAR(result.torque_nm(), 10.0, 0.01);
  EXPECT_GE(result.angle_deg(), 150.0F);
  EXPECT_LE(result.angle_deg(), 200.0F);
  EXPECT_EQ(result.nok_reasons(), "");
  EXPECT_EQ(result.run_counter(), 1);
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(SmartToolLogicTest, RepeatingTheSameTightenIsOneTighteningAndANewRunIdIsTheNext) {
  make_ready();
  const Order bolt7 = tighten(7);
  ASSERT_TRUE(tighten_to_the_end(bolt7));
  ASSERT_EQ(tool_->snapshot().run_counter, 1);
  // The planner keeps repeating its command (state-based): nothing more happens.
  cycles(bolt7, 40);
  EXPECT_EQ(tool_->snapshot().run_counter, 1) << "no second run for the same run_id";
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(state_.last_result().run_id(), 7u);
  EXPECT_FALSE(fake_->history("tool.run_forward").empty());
  const std::size_t edges = fake_->history("tool.run_forward").size();

  const Order bolt8 = tighten(8);
  ASSERT_TRUE(tighten_to_the_end(bolt8));
  EXPECT_EQ(tool_->snapshot().run_counter, 2);
  EXPECT_EQ(state_.last_result().run_id(), 8u);
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_EQ(fake_->history("tool.run_forward").size(), edges + 2) << "one more on/off of the run line";
}

TEST_F(SmartToolLogicTest, ANewRunIdDuringARunStopsItNokAndStartsTheNext) {
  make_ready();
  const Order bolt7 = tighten(7);
  ASSERT_TRUE(cycle_until(&bolt7, [&] { return tool_->snapshot().running; }));
  const Order bolt8 = tighten(8);
  cycle(&bolt8);
  EXPECT_EQ(output(), "idle") << "the run lines drop at once";
  EXPECT_EQ(std::string(state_.activity()), "stopping");
  ASSERT_TRUE(cycle_until(&bolt8, [&] { return state_.last_result().run_id() == 7; }));
  EXPECT_FALSE(state_.last_result().ok());
  EXPECT_EQ(state_.last_result().nok_reasons(), "torque low, stopped by command");
  ASSERT_TRUE(tighten_to_the_end(bolt8));
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_EQ(tool_->snapshot().run_counter, 2);
}

TEST_F(SmartToolLogicTest, ASlippingJointEndsNok) {
  make_ready();
  tool_->set_joint_slip(true);
  const Order bolt3 = tighten(3);
  ASSERT_TRUE(tighten_to_the_end(bolt3));
  EXPECT_FALSE(state_.last_result().ok());
  EXPECT_EQ(state_.last_result().nok_reasons(), "torque low, angle high");
  EXPECT_LT(state_.last_result().torque_nm(), 10.0F);
}

TEST_F(SmartToolLogicTest, ALoosenRunsInReverseWhileInForce) {
  make_ready();
  const Order loosen = action("loosen");
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; }));
  EXPECT_TRUE(line("tool.run_forward"));
  EXPECT_TRUE(line("tool.run_reverse"));
  cycles(loosen, 10);
  EXPECT_TRUE(tool_->snapshot().running);
  EXPECT_EQ(tool_->snapshot().direction, st::Direction::kReverse);
  const Order idle = action("idle");
  cycle(&idle);
  EXPECT_EQ(output(), "idle");
  ASSERT_TRUE(cycle_until(&idle, [&] { return std::string(state_.activity()) == "idle"; }));
  EXPECT_FALSE(tool_->snapshot().running);
  EXPECT_TRUE(state_.last_result().program().empty()) << "a reverse run has no result";
}

TEST_F(SmartToolLogicTest, TheDirectionNeverChangesWhileTheRunEnableIsOn) {
  make_ready();
  auto forward = fake_->wiring("tool.run_forward");
  auto reverse = fake_->wiring("tool.run_reverse");
  ASSERT_TRUE(forward.is_ok() && reverse.is_ok());
  // Both lines are active-high: electrical level = logical level, in the order they changed.
  ASSERT_TRUE(forward.value().chip->watch(forward.value().line, line_changes_.forward).is_ok());
  ASSERT_TRUE(reverse.value().chip->watch(reverse.value().line, line_changes_.reverse).is_ok());
  const Order loosen = action("loosen");
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; }));
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  cycle(nullptr);
  EXPECT_EQ(output(), "idle");
  // idle -> reverse: R1 F1; reverse -> forward: F0 R0 F1; forward -> idle: F0.
  EXPECT_EQ(line_changes_.sequence, (std::vector<std::string>{"R1", "F1", "F0", "R0", "F1", "F0"}));
  bool enable = false;
  for (const std::string& change : line_changes_.sequence) {
    if (change[0] == 'F') enable = change[1] == '1';
    if (change[0] == 'R') {
      EXPECT_FALSE(enable) << "run_reverse changed with run_forward on";
    }
  }
}

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

// --- safe states -------------------------------------------------------------------------------

TEST_F(SmartToolLogicTest, NoCommandInForceIsIdle) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  cycle(nullptr);  // the watchdog tripped
  EXPECT_EQ(output(), "idle");
  EXPECT_FALSE(line("tool.run_forward"));
  ASSERT_TRUE(cycle_until(nullptr, [&] { return !tool_->snapshot().running; }));
  EXPECT_EQ(state_.last_result().run_id(), 1u);
  EXPECT_FALSE(state_.last_result().ok());
}

TEST_F(SmartToolLogicTest, EnterSafeStateDropsTheRunLines) {
  make_ready();
  const Order loosen = action("loosen");
  ASSERT_TRUE(cycle_until(&loosen, [&] { return output() == "reverse"; }));
  logic_->enter_safe_state();
  EXPECT_FALSE(line("tool.run_forward"));
  EXPECT_FALSE(line("tool.run_reverse"));
  EXPECT_EQ(logic_->output(), RunOutput::kIdle);
}

// --- faults and recovery -----------------------------------------------------------------------

TEST_F(SmartToolLogicTest, AControllerLostMidRunEndsItAndNeedsResetAndAFreshCommand) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  tool_->power_off();
  cycles(bolt1, 6);  // 300 ms: not yet lost
  EXPECT_TRUE(state_.controller_online());
  cycles(bolt1, 2);  // > 350 ms after the last heartbeat
  EXPECT_FALSE(state_.controller_online());
  EXPECT_EQ(output(), "idle");
  EXPECT_NE(errors().find("tool controller lost: no heartbeat for"), std::string::npos) << errors();
  EXPECT_EQ(state_.last_result().run_id(), 1u);
  EXPECT_FALSE(state_.last_result().ok());
  EXPECT_EQ(state_.last_result().nok_reasons(), "controller lost");

  tool_->power_on();  // it reboots: no program, counter 0
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return state_.controller_online(); }));
  const Order bolt2 = tighten(2);
  cycles(bolt2, 5);
  EXPECT_EQ(output(), "idle") << "latched until reset";
  EXPECT_NE(errors().find("tool controller was lost"), std::string::npos) << errors();
  reset_command();
  EXPECT_EQ(errors().find("tool controller"), std::string::npos) << errors();
  ASSERT_TRUE(tighten_to_the_end(bolt2)) << errors();
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_EQ(*tool_->snapshot().program, settings_.programs[0].program) << "selected again after the reboot";
}

TEST_F(SmartToolLogicTest, ABusOffForcesIdleAndLatchesUntilReset) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  fake_->can_network().set_bus_state("vcan-tool", hal::CanBusState::kBusOff);
  cycle(&bolt1);
  EXPECT_EQ(output(), "idle");
  EXPECT_NE(errors().find("CAN bus tool_bus (vcan-tool): bus-off; outputs idle"), std::string::npos)
      << errors();
  EXPECT_EQ(state_.last_result().nok_reasons(), "CAN bus fault");
  fake_->can_network().set_bus_state("vcan-tool", hal::CanBusState::kErrorActive);
  cycles(bolt1, 3);
  EXPECT_NE(errors().find("had a fault (bus-off, down or failed I/O); send reset to clear"),
            std::string::npos)
      << errors();
  const Order bolt2 = tighten(2);
  cycles(bolt2, 4);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "CAN bus fault (latched: send reset)");
  reset_command();
  ASSERT_TRUE(tighten_to_the_end(bolt2)) << errors();
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(SmartToolLogicTest, TheControllersOwnBusOffIsALostControllerAndItsLateResultIsTaken) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  tool_->set_bus_off(true);
  ASSERT_TRUE(cycle_until(
      &bolt1, [&] { return !state_.controller_online(); }, 10));
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(state_.last_result().nok_reasons(), "controller lost");
  tool_->set_bus_off(false);
  // Back on the bus it reports the aborted run: the hub takes its final values.
  ASSERT_TRUE(cycle_until(
      &bolt1, [&] { return std::string(state_.last_result().nok_reasons()) != "controller lost"; }, 10));
  EXPECT_EQ(state_.last_result().nok_reasons(), "torque low, link lost");
  EXPECT_EQ(state_.last_result().run_id(), 1u);
}

TEST_F(SmartToolLogicTest, AControllerAlarmEndsTheRunAndResetClearsItInTheController) {
  make_ready();
  const Order bolt1 = tighten(1);
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
  tool_->raise_alarm(st::alarm_bit::kOvercurrent);
  cycle(&bolt1);
  EXPECT_EQ(output(), "idle");
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return state_.last_result().run_id() == 1; }));
  EXPECT_EQ(state_.last_result().nok_reasons(), "torque low, alarm");
  EXPECT_EQ(state_.controller_alarms(), "overcurrent");
  EXPECT_NE(errors().find("tool controller alarm: overcurrent; outputs idle"), std::string::npos) << errors();
  const Order bolt2 = tighten(2);
  cycles(bolt2, 4);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "tool controller alarm");
  reset_command();
  ASSERT_TRUE(cycle_until(
      &bolt2, [&] { return tool_->snapshot().alarms == 0; }, 5))
      << "Reset alarm sent";
  ASSERT_TRUE(tighten_to_the_end(bolt2)) << errors();
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_TRUE(errors_.empty()) << errors();
}

TEST_F(SmartToolLogicTest, AnUnreadableSummaryAlarmInputForbidsRunning) {
  make_ready();
  auto wiring = fake_->wiring("tool.summary_alarm");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, true).is_ok());
  const Order bolt1 = tighten(1);
  cycles(bolt1, 3);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "summary alarm input unreadable");
  EXPECT_NE(errors().find("input tool.summary_alarm failed to read: i/o error"), std::string::npos)
      << errors();
  ASSERT_TRUE(wiring.value().chip->fail_reads(wiring.value().line, false).is_ok());
  ASSERT_TRUE(cycle_until(&bolt1, [&] { return output() == "forward"; }));
}

TEST_F(SmartToolLogicTest, ARunLineThatCannotBeWrittenIsReported) {
  make_ready();
  auto wiring = fake_->wiring("tool.run_forward");
  ASSERT_TRUE(wiring.is_ok());
  ASSERT_TRUE(wiring.value().chip->fail_writes(wiring.value().line, true).is_ok());
  const Order loosen = action("loosen");
  cycles(loosen, 3);
  EXPECT_EQ(output(), "idle") << "the State shows what the lines show";
  EXPECT_NE(errors().find("run line tool.run_forward: write failed (i/o error)"), std::string::npos)
      << errors();
}

// --- bad commands ------------------------------------------------------------------------------

TEST_F(SmartToolLogicTest, BadTightenCommandsAreRejectedWithTheirReason) {
  runtime::Problem problem;
  hub_msgs::SmartToolCommand command;
  const Order zero = tighten(0);
  command = zero.message();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(),
            "tighten needs a run_id from 1 up (it names the tightening; 0 is reserved for manual runs)");
  const Order unknown = tighten(5, "wheel_nut");
  command = unknown.message();
  EXPECT_FALSE(logic_->validate(command, problem));
  EXPECT_EQ(problem.view(), "unknown program 'wheel_nut' (expected one of: ladder_frame_bolt, pipe_plate)");
  const Order empty = tighten(5, "");
  command = empty.message();
  EXPECT_FALSE(logic_->validate(command, problem));
  const Order good = tighten(5, "pipe_plate");
  command = good.message();
  EXPECT_TRUE(logic_->validate(command, problem));
  // The other actions ignore run_id and program.
  Order idle = action("idle");
  idle.program = "anything";
  command = idle.message();
  EXPECT_TRUE(logic_->validate(command, problem));
}

// --- start-up ----------------------------------------------------------------------------------

TEST_F(SmartToolLogicTest, BeforeTheFirstHeartbeatNothingRunsAndTheStateSaysWhy) {
  // The hub starts while the controller is off (its bus node opened after the controller's last
  // heartbeat), and the controller boots later.
  tool_->power_off();
  logic_.reset();
  auto logic = make_smart_tool_logic(settings_, board_, *fake_, std::make_unique<RspToolHolder>(rsp_),
                                     clock_.now().mono);
  ASSERT_TRUE(logic);
  logic_.emplace(std::move(*logic));
  arm_to_operating();
  const Order bolt1 = tighten(1);
  cycles(bolt1, 10);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "no heartbeat from the tool controller yet");
  EXPECT_NE(errors().find("tool controller (node 1 on tool_bus): no heartbeat since start"),
            std::string::npos)
      << errors();
  tool_->power_on();
  ASSERT_TRUE(tighten_to_the_end(bolt1)) << "not latched: a controller booting after the hub is normal";
  EXPECT_TRUE(state_.last_result().ok());
}

}  // namespace
}  // namespace hubrt::tool_ecu
