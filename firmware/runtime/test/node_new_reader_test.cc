// A node publishes its State at once when a new reader of it matches (issue 16, point 2): the
// match is an event the sink reports and the node takes in its step, like a command, and the
// State it causes counts in the budget of immediate States like a command's.
#include <gtest/gtest.h>

#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;

class NodeNewReaderTest : public ::testing::Test {
 protected:
  NodeNewReaderTest() {
    NodeOptions options;
    options.name = "v1";
    options.immediate_state_interval = milliseconds(10);
    // A bucket of one token: a second State within 10 ms waits (the default burst of
    // ImmediateStateBudget is tested in immediate_state_budget_test.cc).
    options.immediate_state_burst = 1;
    node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  }
  // A step between heartbeats, as Hub::command_step runs it.
  void command_step() {
    const bool took_effect = node_->step(clock_.now());
    ASSERT_TRUE(node_->publish_if_due(clock_.now(), took_effect).is_ok());
  }
  void heartbeat() {
    node_->step(clock_.now());
    ASSERT_TRUE(node_->publish(clock_.now()).is_ok());
  }

  ManualClock clock_;
  ValveWorld world_;
  QueueSource source_;
  CountingSink sink_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::unique_ptr<Node<ValveLogic>> node_;
};

TEST_F(NodeNewReaderTest, ANewReaderGetsAStateAtOnceWithoutWaitingForTheHeartbeat) {
  heartbeat();  // the first cycle at start: written before anyone was there to read it
  ASSERT_EQ(sink_.count, 1u);
  clock_.advance(milliseconds(15));
  command_step();
  EXPECT_EQ(sink_.count, 1u) << "nothing happened: no State between heartbeats";

  sink_.new_reader = true;  // discovery matched a subscriber
  command_step();
  EXPECT_EQ(sink_.count, 2u) << "the new reader's State goes out in the step that took the match";
  EXPECT_EQ(sink_.last_seq, 2u);
  EXPECT_FALSE(sink_.new_reader) << "the node consumed the event";

  clock_.advance(milliseconds(20));
  command_step();
  EXPECT_EQ(sink_.count, 2u) << "one State per match, not one per step";
}

TEST_F(NodeNewReaderTest, AMatchInsideTheBudgetWindowWaitsForItAndIsNotLost) {
  heartbeat();
  clock_.advance(milliseconds(15));
  sink_.new_reader = true;
  command_step();
  ASSERT_EQ(sink_.count, 2u);

  clock_.advance(milliseconds(3));  // a second reader 3 ms later: inside the 10 ms window
  sink_.new_reader = true;
  command_step();
  EXPECT_EQ(sink_.count, 2u) << "held back by the budget of immediate States";
  EXPECT_EQ(node_->states_deferred(), 1u) << "counted like a command's held-back State";

  clock_.advance(milliseconds(8));  // window open again: the next step publishes what waited
  command_step();
  EXPECT_EQ(sink_.count, 3u);
}

TEST_F(NodeNewReaderTest, AMatchTakenInAHeartbeatCycleGoesOutWithTheHeartbeatOnly) {
  heartbeat();
  clock_.advance(milliseconds(100));
  sink_.new_reader = true;
  heartbeat();
  EXPECT_EQ(sink_.count, 2u);
  clock_.advance(milliseconds(15));
  command_step();
  EXPECT_EQ(sink_.count, 2u) << "the heartbeat already reached the new reader";
}

TEST_F(NodeNewReaderTest, AFloodOfMatchesIsCappedByTheBudget) {
  heartbeat();
  for (int i = 0; i < 1000; ++i) {  // a peer creating readers in a loop, one every 0.1 ms
    clock_.advance(std::chrono::microseconds(100));
    sink_.new_reader = true;
    command_step();
  }
  // 100 ms of matches with a 10 ms window: at most 10 (+1 for the first) immediate States.
  EXPECT_LE(sink_.count, 1u + 11u);
  EXPECT_GE(sink_.count, 1u + 9u);
}

}  // namespace
}  // namespace hubrt::runtime::testing
