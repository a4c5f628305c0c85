// The smart tool node's logic on the fake backend (the simulated controller on a virtual CAN bus,
// fake GPIO) with a manual clock (SmartToolLogicTest, smart_tool_test_support.h): the safe
// states, faults (a lost controller, bus-off, a controller alarm, unreadable or unwritable lines)
// and the recovery after a reset, and the start before the controller's first heartbeat.
#include <gtest/gtest.h>

#include "smart_tool_logic.h"
#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

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
