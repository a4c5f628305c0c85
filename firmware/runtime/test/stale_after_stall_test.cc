// The SIGSTOP case of issue 29 under the manual clock: a planner commands "open" at 10 Hz, the
// hub's process is stopped for 4 s while the planner sends for 0.3 s more and then goes away, and
// the commands that queued meanwhile are delivered when the hub runs again. None of them may act:
// the node goes safe on its timeout and stays safe, fresh_msg false, the valve closed — with the
// clocks synced (the commands' ages) and without (the stall rule alone). A live planner's commands
// act again once the hub has caught up; a stall shorter than the command timeout discards nothing.
#include <memory>
#include <optional>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/runtime/manual_cycle_timer.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

// A planner writing "open" every 100 ms from `start` until `stop` (its clock is the hub's): at
// each step it hands the node what it wrote since the last step, as the transport would once the
// hub reads its socket. While the hub is paused nothing is handed over; afterwards all of it is.
class PlannerStage final : public CycleStage {
 public:
  PlannerStage(QueueSource& source, Time start, Time stop) : source_(source), next_(start), stop_(stop) {}
  void before_nodes(const Instant& now) noexcept override {
    while (next_ <= now.mono && next_ <= stop_) {
      const WallTime written{now.wall.ns_since_epoch - (now.mono - next_).count()};
      source_.push(OwnedValveCommand{}, written);
      next_ += milliseconds(100);
    }
  }
  void after_nodes(const Instant& /*now*/, bool /*publish_all*/, bool /*took_effect*/) noexcept override {}

 private:
  QueueSource& source_;
  Time next_;
  Time stop_;
};

// Every State published: when, and what it said.
struct Published {
  Time at;
  std::uint8_t lifecycle;
  bool fresh_msg;
  bool open;
};
class LifecycleRecordingSink final : public StateSink<ValveState> {
 public:
  explicit LifecycleRecordingSink(const ManualClock& clock) : clock_(clock) {}
  Status publish(const ValveState& state) noexcept override {
    states.push_back(Published{clock_.now().mono, state.header.lifecycle, state.fresh_msg, state.open});
    return Status::ok();
  }
  std::vector<Published> states;

 private:
  const ManualClock& clock_;
};

class StaleAfterStallTest : public ::testing::TestWithParam<ClockTolerance> {
 protected:
  // Runs a hub at 100 Hz with one valve node until `end`, the planner sending from 0 to
  // `planner_stop`, the process paused at `pause_at` for `pause`.
  void run(milliseconds planner_stop, milliseconds pause_at, Duration pause, milliseconds end) {
    auto owned_timer = std::make_unique<ManualCycleTimer>(clock_);
    ManualCycleTimer& timer = *owned_timer;
    CycleRunner runner(std::move(owned_timer));
    Hub hub(HubOptions{"test", "hub", milliseconds(10), nullptr});
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = seconds(1);
    options.clock_tolerance = GetParam();
    auto node = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
    const Node<ValveLogic>& added = *node;
    hub.add_node(std::move(node));
    hub.add_first_stage(std::make_unique<PlannerStage>(source_, start_, start_ + planner_stop));
    timer.pause_at(start_ + pause_at, pause);
    timer.request_stop_at(start_ + end);
    auto stopped = runner.run(hub, clock_);
    ASSERT_TRUE(stopped) << stopped.error().message;
    longest_late_ = hub.stats().longest_late;
    commands_stale_ = added.commands_stale();
  }
  [[nodiscard]] std::vector<Published> states_from(Duration offset) const {
    std::vector<Published> out;
    for (const Published& p : sink_.states) {
      if (p.at >= start_ + offset) out.push_back(p);
    }
    return out;
  }

  ManualClock clock_;
  const Time start_ = clock_.now().mono;
  ValveWorld world_;
  QueueSource source_;
  LifecycleRecordingSink sink_{clock_};
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  Duration longest_late_{0};
  std::uint64_t commands_stale_ = 0;
};

constexpr auto kOperational = static_cast<std::uint8_t>(Lifecycle::kOperational);

TEST_P(StaleAfterStallTest, CommandsQueuedDuringASigstopNeverAct) {
  // Stopped at 2.0 s for 4 s; the planner sent until 2.3 s and is gone when the hub continues.
  run(milliseconds(2300), milliseconds(2000), seconds(4), milliseconds(8000));
  const auto before = states_from(milliseconds(1000));
  ASSERT_FALSE(before.empty());
  EXPECT_EQ(before.front().lifecycle, kOperational) << "the planner commanded before the stop";
  EXPECT_TRUE(before.front().open);
  EXPECT_GE(longest_late_, seconds(4) - milliseconds(10)) << "the pause shows as one long overrun";

  const auto after = states_from(milliseconds(6000));
  ASSERT_GT(after.size(), 150u) << "the heartbeat went on after the continue";
  for (const Published& p : after) {
    EXPECT_NE(p.lifecycle, kOperational) << "at " << to_seconds(p.at - start_) << " s";
    EXPECT_FALSE(p.fresh_msg) << "at " << to_seconds(p.at - start_) << " s";
    EXPECT_FALSE(p.open) << "the valve driven by a 4 s old command at " << to_seconds(p.at - start_) << " s";
  }
  EXPECT_GE(commands_stale_, 3u) << "the commands written from 2.0 to 2.3 s were dropped and counted";
}

TEST_P(StaleAfterStallTest, ALivePlannersCommandsActAgainOnceTheHubCaughtUp) {
  // The planner keeps sending through the stop and after it.
  run(milliseconds(9000), milliseconds(2000), seconds(4), milliseconds(8000));
  const auto after = states_from(milliseconds(6000));
  ASSERT_FALSE(after.empty());
  EXPECT_NE(after.front().lifecycle, kOperational) << "the first State after the continue is safe";
  EXPECT_FALSE(after.front().fresh_msg);
  // Commands taken in the first kStallSettle after the continue were queued (or may have been);
  // one taken after it is new and acts.
  const auto late = states_from(milliseconds(6000) + kStallSettle + milliseconds(150));
  ASSERT_FALSE(late.empty());
  EXPECT_EQ(late.front().lifecycle, kOperational);
  EXPECT_TRUE(late.front().fresh_msg);
  EXPECT_TRUE(late.front().open);
}

TEST_P(StaleAfterStallTest, AStallShorterThanTheTimeoutDiscardsNothing) {
  run(milliseconds(9000), milliseconds(2000), milliseconds(500), milliseconds(4000));
  for (const Published& p : states_from(milliseconds(1000))) {
    EXPECT_EQ(p.lifecycle, kOperational) << "at " << to_seconds(p.at - start_) << " s";
  }
  EXPECT_EQ(commands_stale_, 0u);
}

INSTANTIATE_TEST_SUITE_P(ClocksSyncedOrNot, StaleAfterStallTest,
                         ::testing::Values(ClockTolerance(milliseconds(50)), ClockTolerance(std::nullopt)),
                         [](const ::testing::TestParamInfo<ClockTolerance>& param) {
                           return param.param.has_value() ? std::string("Synced") : std::string("NotSynced");
                         });

}  // namespace
}  // namespace hubrt::runtime::testing
