// CycleRunner's schedule, on a ManualCycleTimer: no real time passes, so every instant below is
// exact. What is proved: cycle k runs at start + k·period whatever the cycles took (no drift);
// a cycle that runs past deadlines counts them as overruns and is followed by ONE cycle, not a
// burst; a wake runs a command step at once and leaves the schedule alone; stop and signal end
// the run before a wake pending with them.
#include <csignal>
#include <map>
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/runtime/manual_cycle_timer.h"

namespace hubrt::runtime {
namespace {

using std::chrono::milliseconds;

// Records when the hub stepped (periodic cycle or command step) and makes a step "take" time by
// advancing the manual clock, as a slow device call would.
class WorkStage final : public CycleStage {
 public:
  explicit WorkStage(ManualClock& clock) : clock_(clock) {}
  void before_nodes(const Instant& /*now*/) noexcept override {}
  void after_nodes(const Instant& now, bool publish_all, bool /*took_effect*/) noexcept override {
    (publish_all ? cycles : command_steps).push_back(now.mono);
    const std::size_t index = cycles.size() + command_steps.size() - 1;
    const auto slow = slow_steps.find(index);
    clock_.advance(slow != slow_steps.end() ? slow->second : work);
  }

  Duration work{0};                            // what every step takes
  std::map<std::size_t, Duration> slow_steps;  // step index (0-based, all steps) -> what it takes
  std::vector<Time> cycles;
  std::vector<Time> command_steps;

 private:
  ManualClock& clock_;
};

struct Fixture {
  Fixture() {
    auto owned_timer = std::make_unique<ManualCycleTimer>(clock);
    timer = owned_timer.get();
    runner = std::make_unique<CycleRunner>(std::move(owned_timer));
    auto owned_stage = std::make_unique<WorkStage>(clock);
    stage = owned_stage.get();
    hub.add_stage(std::move(owned_stage));
  }
  [[nodiscard]] Time at(milliseconds offset) const { return start + offset; }
  std::vector<Time> at(std::initializer_list<int> offsets_ms) const {
    std::vector<Time> out;
    for (const int ms : offsets_ms) out.push_back(at(milliseconds(ms)));
    return out;
  }

  ManualClock clock;
  const Time start = clock.now().mono;
  Hub hub{HubOptions{"test", "hub", milliseconds(10), nullptr}};
  ManualCycleTimer* timer = nullptr;
  std::unique_ptr<CycleRunner> runner;
  WorkStage* stage = nullptr;
};

TEST(CycleRunnerSchedule, CyclesRunOnAbsoluteDeadlinesWhateverTheyTake) {
  Fixture f;
  f.stage->work =
      milliseconds(3);  // a runner that slept one period after each cycle would drift 3 ms a cycle
  f.timer->request_stop_at(f.at(milliseconds(45)));
  auto stopped = f.runner->run(f.hub, f.clock);
  ASSERT_TRUE(stopped) << stopped.error().message;
  EXPECT_EQ(*stopped, StopReason::kRequested);
  EXPECT_EQ(f.stage->cycles, f.at({0, 10, 20, 30, 40}));
  EXPECT_EQ(f.hub.stats().cycles, 5u);
  EXPECT_EQ(f.hub.stats().overruns, 0u);
  EXPECT_EQ(f.clock.now().mono, f.at(milliseconds(45)));
}

TEST(CycleRunnerSchedule, ALateCycleCountsTheDeadlinesItMissedAndIsFollowedByOneCycle) {
  Fixture f;
  // The cycle at 10 ms takes 35 ms (until 45): the deadlines at 20 and 30 pass unserved
  // (overruns), the one at 40 is served late, at once, by ONE cycle; then the schedule goes on at
  // 50 — not at 55 (drift) and not with catch-up cycles at 45, 45, 45.
  f.stage->slow_steps[1] = milliseconds(35);
  f.timer->request_stop_at(f.at(milliseconds(65)));
  auto stopped = f.runner->run(f.hub, f.clock);
  ASSERT_TRUE(stopped) << stopped.error().message;
  EXPECT_EQ(f.stage->cycles, f.at({0, 10, 45, 50, 60}));
  EXPECT_EQ(f.hub.stats().overruns, 2u);
  EXPECT_EQ(f.hub.stats().cycles, 5u);
}

TEST(CycleRunnerSchedule, ACycleThatEndsExactlyOnTheNextDeadlineIsNoOverrun) {
  Fixture f;
  f.stage->slow_steps[0] = milliseconds(10);  // ends at 10, the next deadline itself
  f.stage->slow_steps[1] = milliseconds(20);  // ends at 30: the deadline at 20 was missed
  f.timer->request_stop_at(f.at(milliseconds(35)));
  ASSERT_TRUE(f.runner->run(f.hub, f.clock));
  EXPECT_EQ(f.stage->cycles, f.at({0, 10, 30}));
  EXPECT_EQ(f.hub.stats().overruns, 1u);
}

TEST(CycleRunnerSchedule, AWakeRunsACommandStepAtOnceAndLeavesTheScheduleAlone) {
  Fixture f;
  f.stage->work = milliseconds(2);
  f.timer->wake_at(f.at(milliseconds(13)));
  f.timer->request_stop_at(f.at(milliseconds(35)));
  ASSERT_TRUE(f.runner->run(f.hub, f.clock));
  EXPECT_EQ(f.stage->command_steps, f.at({13}));
  EXPECT_EQ(f.stage->cycles, f.at({0, 10, 20, 30}));
  EXPECT_EQ(f.hub.stats().command_steps, 1u);
  EXPECT_EQ(f.hub.stats().overruns, 0u);
}

TEST(CycleRunnerSchedule, AWakeDuringACycleIsServedRightAfterIt) {
  Fixture f;
  const Waker waker = f.runner->waker();
  RunHooks hooks;
  int cycles = 0;
  // A transport's thread calls wake() while the cycle runs; here the hook after cycle 2 stands in.
  hooks.after_cycle = [&](const Instant&) {
    if (++cycles == 2) waker.wake();
  };
  f.stage->work = milliseconds(4);
  f.timer->request_stop_at(f.at(milliseconds(25)));
  ASSERT_TRUE(f.runner->run(f.hub, f.clock, hooks));
  EXPECT_EQ(f.stage->cycles, f.at({0, 10, 20}));
  EXPECT_EQ(f.stage->command_steps, f.at({14}));  // when cycle 2 ended, not at the next deadline
}

TEST(CycleRunnerSchedule, AStopEndsTheRunBeforeAWakePendingWithIt) {
  Fixture f;
  f.timer->wake_at(f.at(milliseconds(15)));
  f.timer->request_stop_at(f.at(milliseconds(15)));
  auto stopped = f.runner->run(f.hub, f.clock);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(*stopped, StopReason::kRequested);
  EXPECT_TRUE(f.stage->command_steps.empty());
  EXPECT_EQ(f.stage->cycles, f.at({0, 10}));
  EXPECT_EQ(f.runner->last_signal(), 0);
}

TEST(CycleRunnerSchedule, AStopSignalEndsTheRunAndIsReported) {
  Fixture f;
  f.timer->wake_at(f.at(milliseconds(20)));
  f.timer->signal_at(f.at(milliseconds(20)), SIGTERM);
  auto stopped = f.runner->run(f.hub, f.clock);
  ASSERT_TRUE(stopped);
  EXPECT_EQ(*stopped, StopReason::kSignal);
  EXPECT_EQ(f.runner->last_signal(), SIGTERM);
  EXPECT_EQ(f.stage->cycles, f.at({0, 10}));  // the deadline at 20 came with the signal: no cycle
  EXPECT_TRUE(f.stage->command_steps.empty());
}

}  // namespace
}  // namespace hubrt::runtime
