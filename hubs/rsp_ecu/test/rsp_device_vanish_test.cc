// The RSP ECU's GPIO chip vanishes (an expander unplugged, its driver unbound) while the planner
// holds the changer open: in the very next cycle the logic reports the devices missing (or the
// pressure failure their loss latches), so the node leaves operational and the runtime hands the
// logic no command — the node's safe state, one period after the loss. A vanished output drives
// nothing (the wiring makes undriven = safe). Writes its row of docs/safety.md's time-to-safe table.
#include <gtest/gtest.h>

#include "hubrt/test_support/time_to_safe.h"

#include "rsp_test_support.h"

namespace hubrt::rsp_ecu::testing {
namespace {

using std::chrono::milliseconds;

TEST_F(RspLogicTest, AVanishedChipTakesTheNodeOutOfOperationInTheNextCycle) {
  RspLogic logic = make_logic();
  dock_reports(true, true, true);
  OwnedCommand unlock = command("unlock");
  run_for(logic, milliseconds(300), &unlock);
  ASSERT_TRUE(lock_valve_energised());
  ASSERT_EQ(logic.condition(), runtime::NodeCondition::kOk);

  auto wiring = fake_->wiring("rsp.lock_valve");
  ASSERT_TRUE(wiring.is_ok());
  const Time gone = clock_.now().mono;
  wiring.value().chip->vanish();
  int cycles = 0;
  while (logic.condition() == runtime::NodeCondition::kOk && cycles < 100) {
    clock_.advance(kCycle);
    cycle(logic, &unlock);
    ++cycles;
  }
  EXPECT_EQ(cycles, 1) << "the loss is seen in the first cycle after it";
  EXPECT_NE(logic.condition(), runtime::NodeCondition::kOk);
  EXPECT_TRUE(errors_.contains("output rsp.lock_valve not available:")) << errors_.at(0);
  const Duration to_safe = clock_.now().mono - gone;
  test_support::record_time_to_safe(
      "device_vanish_rsp",
      test_support::TimeToSafe{"the GPIO chip vanishes under a command (changer open)", "rsp_ecu",
                               "lock and gripper valves: no longer driven (undriven = safe by wiring)",
                               "the supervised devices report the loss; the node leaves operational "
                               "(recovering/fault) and gets no command",
                               to_seconds(to_safe), to_seconds(kCycle), "one period (manual clock)",
                               "hubrt_rsp_ecu_device_vanish_test"});
}

}  // namespace
}  // namespace hubrt::rsp_ecu::testing
