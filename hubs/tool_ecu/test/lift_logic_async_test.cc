// How the lift logic meets its asynchronous Modbus device: it talks to the drive only from its
// cycle, one request in flight at a time; a reading is as old as the request that fetched it; a
// request past its deadline is a timeout. On old main the lift had a worker thread of its own that
// read the drive (and stamped the reading with its clock) whenever it liked.
#include <gtest/gtest.h>

#include "lift_logic_fixture.h"

namespace hubrt::tool_ecu::testing {
namespace {

// Nothing happens between cycles: no thread of the logic's reaches the drive. A cycle submits at
// most one request and never a second while one is in flight.
TEST_F(LiftLogicTest, TheLogicTalksToTheDriveOnlyFromItsCycle) {
  start();
  EXPECT_TRUE(script_.submitted().empty()) << "creating the logic sends nothing";
  const Order work = move("work");
  cycle(&work);
  ASSERT_EQ(script_.submitted().size(), 1u);
  const hal::ModbusBatch& first = script_.submitted()[0];
  EXPECT_EQ(first.read_bank, hal::ModbusRegisterBank::kInput);
  EXPECT_EQ(first.read_address, 0);
  EXPECT_EQ(first.read_count, ld::input::kCount);
  EXPECT_EQ(first.write_count, 0) << "no write before the drive's state is known";
  for (int i = 0; i < 2; ++i) {  // 200 ms, inside the request's deadline (300 ms)
    clock_.advance(kStep);
    cycle(&work);
  }
  EXPECT_EQ(script_.submitted().size(), 1u) << "one request in flight at a time";
  EXPECT_EQ(logic_->snapshot().rounds, 0u);
  EXPECT_EQ(drive_control_word(), 0) << "the drive heard nothing";

  script_.complete(clock_.now().mono);
  EXPECT_EQ(logic_->snapshot().rounds, 0u) << "a completion is taken by the cycle, not pushed into the logic";
  clock_.advance(kStep);
  cycle(&work);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_TRUE(state_.drive_online());
  ASSERT_EQ(script_.submitted().size(), 2u);
  EXPECT_EQ(script_.submitted()[1].write_count, ld::holding::kCount);
  EXPECT_EQ(submitted_control_word(), ld::control::kEnable | ld::control::kMove);
  EXPECT_EQ(script_.submitted()[1].write_values[ld::holding::kTargetPosition], 1200);
}

// A reading is as old as the request that fetched it: judged from the time the logic submitted it,
// however late the cycle takes the completion.
TEST_F(LiftLogicTest, ACompletionOlderThanAnswerWithinReadsUnknown) {
  start();
  const Order home = move("home");
  const Time submitted = clock_.now().mono;
  cycle(&home);
  script_.complete(submitted + milliseconds(10));  // the drive answered at once...
  clock_.set(submitted + milliseconds(501));       // ...but the cycle came 501 ms later
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_TRUE(logic_->snapshot().answered);
  EXPECT_EQ(logic_->snapshot().read_at, submitted);
  EXPECT_FALSE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), 501u);
  EXPECT_EQ(state_.fault_text(), "unknown");
  EXPECT_FALSE(state_.in_position()) << "the drive is in position, but that reading is too old to say so";
  EXPECT_NE(errors().find("not answering for 0.50 s"), std::string::npos) << errors();

  // The same answer taken 500 ms after its request is current.
  close();
  DriveScript script(drive_);
  auto logic = LiftLogic::create(settings_, script.open(), clock_.now().mono);
  ASSERT_TRUE(logic) << logic.error().message;
  const Time again = clock_.now().mono;
  command_ = home.message();
  logic->read_inputs(again);
  const hub_msgs::LiftCommandView in_force = command_.view();
  logic->update(&in_force, again);
  script.complete(again + milliseconds(10));
  logic->read_inputs(again + milliseconds(500));
  state_ = hub_msgs::LiftState();
  errors_.clear();
  logic->report(state_, errors_, again + milliseconds(500));
  EXPECT_TRUE(state_.drive_online());
  EXPECT_EQ(state_.reading_age_ms(), 500u);
  EXPECT_TRUE(state_.in_position());
  EXPECT_EQ(state_.fault_text(), "");
}

// A request the device never completes is reported as timed out at its deadline (the time the
// logic submitted it plus the request timeout), and the logic asks again.
TEST_F(LiftLogicTest, ARequestPastItsDeadlineIsATimeoutAndTheLogicAsksAgain) {
  start();
  const Order home = move("home");
  cycle(&home);
  clock_.advance(milliseconds(300));
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 0u) << "deadline not passed yet";
  EXPECT_EQ(script_.submitted().size(), 1u);
  clock_.advance(milliseconds(1));
  cycle(&home);
  EXPECT_EQ(logic_->snapshot().rounds, 1u);
  EXPECT_EQ(logic_->snapshot().last_error, ErrorCode::kTimeout);
  EXPECT_EQ(script_.submitted().size(), 2u) << "asked again in the same cycle";
  script_.complete(clock_.now().mono);
  step(&home);
  EXPECT_TRUE(state_.drive_online());
  EXPECT_EQ(logic_->snapshot().failures_in_a_row, 0u);
}

}  // namespace
}  // namespace hubrt::tool_ecu::testing
