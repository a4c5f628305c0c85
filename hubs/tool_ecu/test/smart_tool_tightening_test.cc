// The smart tool node's logic on the fake backend (the simulated controller on a virtual CAN bus,
// fake GPIO) with a manual clock (SmartToolLogicTest, smart_tool_test_support.h): tightenings
// and their identity (one run per run_id, its result reported), loosening, the run direction, and
// tighten commands rejected with their reason.
#include <gtest/gtest.h>

#include "smart_tool_logic.h"
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

}  // namespace
}  // namespace hubrt::tool_ecu
