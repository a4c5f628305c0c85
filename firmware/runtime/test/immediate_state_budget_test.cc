// The budget of immediate States (issue 11): a planner flipping its command at kHz rates must not
// turn a hub into a State flood, and a well-behaved planner must not notice the budget at all.
// Driven by a ManualClock through Hub, as hubd's CycleRunner drives it.
#include "hubrt/runtime/immediate_state_budget.h"

#include <algorithm>
#include <optional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

// Records when each State was published, what it echoed and whether the heartbeat published it
// (the test sets `in_cycle` around Hub::cycle()).
class RecordingSink final : public StateSink<ValveState> {
 public:
  explicit RecordingSink(const ManualClock& clock) : clock_(clock) {}
  Status publish(const ValveState& state) noexcept override {
    published.push_back({clock_.now().mono, std::string(state.echo.action), in_cycle});
    return Status::ok();
  }
  struct Published {
    Time at;
    std::string echo;
    bool heartbeat;
  };
  std::vector<Published> published;
  bool in_cycle = false;

 private:
  const ManualClock& clock_;
};

constexpr auto kPeriod = milliseconds(100);
constexpr auto kBudget = milliseconds(10);

class BudgetTest : public ::testing::Test {
 protected:
  BudgetTest() {
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = milliseconds(1000);
    options.immediate_state_interval = kBudget;
    auto node = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
    node_ = node.get();
    hub_.add_node(std::move(node));
  }

  void command(const char* action) {
    OwnedValveCommand c;
    c.action = action;
    source_.push(c);
  }
  // Runs the hub from now to now + `span` the way CycleRunner does: a cycle at every period
  // boundary, and between them a command step every `command_every` with `action_at(i)` queued.
  template <class ActionAt>
  void run(Duration span, Duration command_every, ActionAt action_at) {
    const Time end = clock_.now().mono + span;
    int i = 0;
    while (clock_.now().mono < end) {
      if (clock_.now().mono >= next_cycle_) {
        heartbeats_.push_back(clock_.now().mono);
        sink_.in_cycle = true;
        hub_.cycle(clock_.now());
        sink_.in_cycle = false;
        next_cycle_ += kPeriod;
      }
      if (const char* action = action_at(i++); action != nullptr) {
        command(action);
        hub_.command_step(clock_.now());
      }
      clock_.advance(command_every);
    }
  }

  ManualClock clock_;
  ValveWorld world_;
  QueueSource source_;
  RecordingSink sink_{clock_};
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  Hub hub_{HubOptions{"test", "hub", kPeriod, nullptr}};
  Node<ValveLogic>* node_ = nullptr;
  Time next_cycle_ = clock_.now().mono;
  std::vector<Time> heartbeats_;
};

TEST_F(BudgetTest, AFloodOfAlternatingCommandsStaysWithinOneImmediateStatePerIntervalAndTheHeartbeatGoesOn) {
  // Two writers alternating open/close at 5 kHz each: a command every 100 us for one second.
  run(std::chrono::seconds(1), microseconds(100), [](int i) { return i % 2 == 0 ? "open" : "close"; });

  std::size_t immediate = 0;
  std::optional<Time> last_immediate;
  for (const auto& p : sink_.published) {
    if (p.heartbeat) continue;
    ++immediate;
    if (last_immediate) {
      EXPECT_GE(p.at - *last_immediate, kBudget) << "two immediate States closer than the budget";
    }
    last_immediate = p.at;
  }
  // One second: at most one immediate State per 10 ms window, and 10 heartbeats at 100 ms.
  EXPECT_LE(immediate, 100u);
  EXPECT_GE(immediate, 90u) << "the flood still gets its States at the budget's pace";
  ASSERT_EQ(heartbeats_.size(), 10u);
  for (const Time beat : heartbeats_) {
    EXPECT_EQ(std::count_if(sink_.published.begin(), sink_.published.end(),
                            [&](const auto& p) { return p.heartbeat && p.at == beat; }),
              1)
        << "every heartbeat publishes, budget or not";
  }
  // Before the budget (issue 11) every one of the 10,000 changes published a State at once; now
  // every change that did not is counted (for /diagnostics).
  EXPECT_EQ(node_->states_deferred(), 10'000u - immediate);
  EXPECT_EQ(hub_.states_deferred(), node_->states_deferred());
}

TEST_F(BudgetTest, TheLatestCommandWinsAtOnceAndTheNextStateEchoesIt) {
  run(milliseconds(50), microseconds(100), [](int i) { return i % 2 == 0 ? "open" : "close"; });
  clock_.advance(kBudget);  // quiet for one window: the next change publishes at once
  command("open");
  hub_.command_step(clock_.now());
  command("close");
  clock_.advance(microseconds(100));
  hub_.command_step(clock_.now());
  EXPECT_FALSE(world_.open) << "the command took effect at once; only its State waits";
  EXPECT_EQ(sink_.published.back().echo, "open") << "the State of 'close' was held back";
  const std::size_t before = sink_.published.size();
  // No more commands: the next State is the heartbeat, and it echoes the latest command.
  run(kPeriod, milliseconds(1), [](int) -> const char* { return nullptr; });
  ASSERT_GT(sink_.published.size(), before);
  EXPECT_EQ(sink_.published[before].echo, "close");
  EXPECT_TRUE(sink_.published[before].heartbeat);
}

TEST_F(BudgetTest, AHeldBackChangeGoesOutWithTheFirstStepAfterTheWindowEvenForARepeat) {
  command("open");
  hub_.command_step(clock_.now());  // first change: at once
  clock_.advance(milliseconds(1));
  command("close");
  hub_.command_step(clock_.now());  // 1 ms later: held back
  ASSERT_EQ(sink_.published.size(), 1u);
  EXPECT_EQ(node_->states_deferred(), 1u);
  clock_.advance(milliseconds(5));
  command("close");
  hub_.command_step(clock_.now());  // a repeat, still inside the window: nothing
  EXPECT_EQ(sink_.published.size(), 1u);
  clock_.advance(kBudget);
  command("close");
  hub_.command_step(clock_.now());  // a repeat after the window: the held-back State goes out
  ASSERT_EQ(sink_.published.size(), 2u);
  EXPECT_EQ(sink_.published[1].echo, "close");
  EXPECT_EQ(node_->states_deferred(), 1u) << "a repeat is no change and is never counted";
  clock_.advance(kBudget);
  command("close");
  hub_.command_step(clock_.now());
  EXPECT_EQ(sink_.published.size(), 2u) << "nothing is waiting any more: repeats stay silent";
}

TEST_F(BudgetTest, APlannerCommandingEvery20To120MsNeverWaitsForTheBudget) {
  // Commands every 2 ms of simulated time; a change every 20..120 ms (and one pair bunched up to
  // 12 ms apart by delivery jitter), repeats in between, as a planner writes them.
  const std::vector<int> change_at_ms{0, 20, 32, 52, 172, 192, 300, 420, 440, 452};
  std::vector<Time> changed_at;
  const Time start = clock_.now().mono;
  int changes = 0;
  run(milliseconds(500), milliseconds(2), [&](int i) -> const char* {
    const int ms = 2 * i;
    if (std::find(change_at_ms.begin(), change_at_ms.end(), ms) != change_at_ms.end()) {
      ++changes;
      changed_at.push_back(start + milliseconds(ms));
    }
    return changes % 2 == 1 ? "open" : "close";
  });
  EXPECT_EQ(node_->states_deferred(), 0u);
  for (const Time t : changed_at) {
    EXPECT_TRUE(
        std::any_of(sink_.published.begin(), sink_.published.end(), [&](const auto& p) { return p.at == t; }))
        << "the change at " << to_seconds(t - start) * 1e3 << " ms was not published at once";
  }
}

TEST(ImmediateStateBudget, AZeroIntervalAllowsEveryChangeAndTheHeartbeatClearsWhatWaits) {
  ManualClock clock;
  ImmediateStateBudget none(Duration::zero());
  for (int i = 0; i < 5; ++i) EXPECT_TRUE(none.publish_now(clock.now().mono, true));
  EXPECT_FALSE(none.publish_now(clock.now().mono, false)) << "no change, nothing to publish";

  ImmediateStateBudget budget(kBudget);
  EXPECT_TRUE(budget.publish_now(clock.now().mono, true));
  EXPECT_FALSE(budget.publish_now(clock.now().mono, true));
  EXPECT_TRUE(budget.held_back());
  budget.on_heartbeat();
  EXPECT_FALSE(budget.held_back());
  clock.advance(kBudget);
  EXPECT_FALSE(budget.publish_now(clock.now().mono, false)) << "the heartbeat already carried the change";
  EXPECT_EQ(budget.deferred(), 1u);
}

}  // namespace
}  // namespace hubrt::runtime::testing
