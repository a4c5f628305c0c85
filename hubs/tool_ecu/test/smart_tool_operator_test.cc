// The smart tool's collaborative interlock (settings' operator_state): the planner's runs only
// while the operator hub's State says an operator is verified; nobody verified, logged out mid-run
// or the operator hub's State lost all stop the tool, on the manual clock (smart_tool_test_support.h).
#include <gtest/gtest.h>

#include "operator_presence.h"
#include "smart_tool_logic.h"
#include "smart_tool_test_support.h"

namespace hubrt::tool_ecu {
namespace {

using namespace testing;  // NOLINT(google-build-using-namespace): the fixture and its helpers

class SmartToolOperatorTest : public SmartToolLogicTest {
 protected:
  void SetUp() override {
    SmartToolLogicTest::SetUp();
    if (HasFatalFailure()) return;
    logic_->require_operator(std::make_unique<OperatorPanelPresence>(panel_));
  }

  // The operator hub's State says whether someone is verified; fresh as of now.
  void set_verified(bool verified) {
    hub_msgs::OperatorPanelStateRef(*static_cast<hub_msgs::OperatorPanelState::Wire*>(panel_.sample_data()))
        .set_operator_verified(verified);
    panel_.note_arrival(clock_.now().mono);
  }
  // Cycles with the panel's State arriving each time (as at the operator hub's rate), or not.
  void cycles_with_panel(const Order& order, int n, bool panel_alive = true) {
    for (int i = 0; i < n; ++i) {
      if (panel_alive) panel_.note_arrival(clock_.now().mono);
      cycle(&order);
    }
  }

  hub_api::RemoteState<hub_msgs::OperatorPanelStateView> panel_{
      "operator", "/operator_hub/panel/state", milliseconds(500), hub_msgs_msg_dds__OperatorPanelState__desc,
      0};
};

TEST_F(SmartToolOperatorTest, TheToolRunsOnlyWhileAnOperatorIsVerified) {
  make_ready();
  set_verified(false);
  const Order bolt1 = tighten(1);
  cycles_with_panel(bolt1, 10);
  EXPECT_EQ(output(), "idle");
  EXPECT_FALSE(tool_->snapshot().running);
  EXPECT_EQ(tool_->snapshot().run_counter, 0);
  EXPECT_EQ(blocked_by(), "no verified operator: the operator hub reports nobody verified");

  set_verified(true);
  for (int i = 0; i < 100 && !(state_.last_result().run_id() == 1 && output() == "idle"); ++i) {
    cycles_with_panel(bolt1, 1);
  }
  EXPECT_EQ(state_.last_result().run_id(), 1U);
  EXPECT_TRUE(state_.last_result().ok());
  EXPECT_EQ(blocked_by(), "");
}

TEST_F(SmartToolOperatorTest, AnOperatorLoggedOutMidRunStopsTheTool) {
  make_ready();
  set_verified(true);
  const Order bolt1 = tighten(1);
  for (int i = 0; i < 20 && output() != "forward"; ++i) cycles_with_panel(bolt1, 1);
  ASSERT_EQ(output(), "forward");
  set_verified(false);
  cycles_with_panel(bolt1, 1);
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by(), "no verified operator: the operator hub reports nobody verified");
  for (int i = 0; i < 40 && state_.last_result().run_id() != 1; ++i) cycles_with_panel(bolt1, 1);
  EXPECT_EQ(state_.last_result().run_id(), 1U);
  EXPECT_FALSE(state_.last_result().ok());
  // The same run is not started again when the operator comes back.
  set_verified(true);
  cycles_with_panel(bolt1, 10);
  EXPECT_EQ(tool_->snapshot().run_counter, 1);
}

TEST_F(SmartToolOperatorTest, ALostOperatorHubStateCountsAsNobodyVerified) {
  make_ready();
  set_verified(true);
  const Order bolt1 = tighten(1);
  cycles_with_panel(bolt1, 12, /*panel_alive=*/false);  // 600 ms without a State: lost after 500
  EXPECT_EQ(output(), "idle");
  EXPECT_EQ(blocked_by().rfind(
                "no verified operator: input 'operator' (/operator_hub/panel/state): no State for", 0),
            0U)
      << blocked_by();
}

}  // namespace
}  // namespace hubrt::tool_ecu
