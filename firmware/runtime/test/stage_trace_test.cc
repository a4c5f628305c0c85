// The hub's stage trace (stage_trace.h) on a ManualCycleTimer: a command step's stamps are the
// wake, the wait's return, the moment the node that took the command stepped and the moment its
// State was written, in that order and at the instants the step's work put them; a step in which
// no command took effect has no stepped/written stamp; periodic cycles are not recorded; the ring
// keeps the newest; the CSV carries every record; a traced command step allocates nothing.
#include "hubrt/runtime/stage_trace.h"

#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/runtime/cycle_runner.h"
#include "hubrt/runtime/manual_cycle_timer.h"

#include "alloc_counter.h"

namespace hubrt::runtime {
namespace {

using std::chrono::milliseconds;

// A node whose step takes 2 ms and whose publish takes 1 ms of the manual clock; whether a step's
// command takes effect is set per step.
class TimedNode final : public NodeBase {
 public:
  explicit TimedNode(ManualClock& clock) : clock_(clock) {}
  std::string_view name() const noexcept override { return "timed"; }
  std::string_view type() const noexcept override { return "test"; }
  bool step(const Instant& /*now*/) noexcept override {
    clock_.advance(milliseconds(2));
    return take_effect;
  }
  Status publish(const Instant& /*now*/) noexcept override {
    clock_.advance(milliseconds(1));
    return Status::ok();
  }
  Status publish_if_due(const Instant& now, bool took_effect) noexcept override {
    return took_effect ? publish(now) : Status::ok();
  }
  void enter_safe_state() noexcept override {}
  Health health() const noexcept override { return Health::kOk; }
  std::string_view first_error() const noexcept override { return {}; }
  std::uint64_t published() const noexcept override { return 0; }
  std::uint64_t rejected() const noexcept override { return 0; }
  std::uint64_t states_deferred() const noexcept override { return 0; }

  bool take_effect = true;

 private:
  ManualClock& clock_;
};

struct Fixture {
  explicit Fixture(std::size_t capacity) : trace(capacity, clock) {
    auto owned = std::make_unique<ManualCycleTimer>(clock);
    timer = owned.get();
    runner = std::make_unique<CycleRunner>(std::move(owned));
    runner->trace_stages(&trace);
    auto owned_node = std::make_unique<TimedNode>(clock);
    node = owned_node.get();
    hub.add_node(std::move(owned_node));
  }
  ManualClock clock;
  const Time start = clock.now().mono;
  StageTrace trace;
  ManualCycleTimer* timer = nullptr;
  std::unique_ptr<CycleRunner> runner;
  Hub hub{HubOptions{"test", "hub", milliseconds(100), nullptr}};
  TimedNode* node = nullptr;
};

TEST(StageTrace, StampsTheWakeTheReturnTheStepAndTheWriteOfACommandStep) {
  Fixture f(8);
  const Waker waker = f.runner->waker();
  f.hub.cycle(f.clock.now());  // the first periodic cycle is not a command step
  f.clock.set(f.start + milliseconds(10));
  waker.wake();  // Cyclone's listener, at +10 ms; the cycle thread gets going 1 ms later
  f.clock.advance(milliseconds(1));
  f.timer->request_stop_at(f.start + milliseconds(50));
  ASSERT_TRUE(f.runner->run(f.hub, f.clock));
  const auto records = f.trace.records();
  ASSERT_EQ(records.size(), 1U) << "periodic cycles are not recorded";
  const StageRecord& r = records.front();
  EXPECT_EQ(r.listener, f.start + milliseconds(10));
  EXPECT_EQ(r.woke, f.start + milliseconds(11));
  EXPECT_EQ(r.stepped, f.start + milliseconds(13));  // the step's 2 ms
  EXPECT_EQ(r.written, f.start + milliseconds(14));  // the write's 1 ms
  EXPECT_EQ(f.trace.steps(), 1U);
}

TEST(StageTrace, AStepInWhichNoCommandTookEffectHasNoStepOrWriteStamp) {
  Fixture f(8);
  f.node->take_effect = false;
  const Waker waker = f.runner->waker();
  waker.wake();
  f.timer->request_stop_at(f.start + milliseconds(50));
  ASSERT_TRUE(f.runner->run(f.hub, f.clock));
  const auto records = f.trace.records();
  ASSERT_EQ(records.size(), 1U);
  EXPECT_EQ(records.front().listener, f.start);
  EXPECT_EQ(records.front().stepped, Time{});
  EXPECT_EQ(records.front().written, Time{});
}

TEST(StageTrace, TheRingKeepsTheNewestAndTheCsvCarriesThem) {
  Fixture f(2);
  for (int i = 1; i <= 3; ++i) {
    f.trace.note_wake();
    f.trace.begin_step(f.clock.now().mono);
    f.clock.advance(milliseconds(i));
    f.trace.node_stepped();
    f.trace.state_written();
    f.trace.end_step();
    f.clock.advance(milliseconds(10));
  }
  EXPECT_EQ(f.trace.steps(), 3U);
  const auto records = f.trace.records();
  ASSERT_EQ(records.size(), 2U);
  EXPECT_EQ(records[0].stepped - records[0].woke, milliseconds(2));
  EXPECT_EQ(records[1].stepped - records[1].woke, milliseconds(3));

  const auto path =
      std::filesystem::temp_directory_path() / ("hubrt-stage-trace-" + std::to_string(getpid()));
  ASSERT_TRUE(f.trace.write_csv(path.string()));
  std::ifstream in(path);
  std::stringstream text;
  text << in.rdbuf();
  std::filesystem::remove(path);
  const std::string csv = text.str();
  EXPECT_NE(csv.find("# hubd stage trace: 3 command steps, the last 2 kept\n"), std::string::npos) << csv;
  EXPECT_NE(csv.find("listener_ns,woke_ns,stepped_ns,written_ns\n"), std::string::npos);
  const std::string last = std::to_string(records[1].listener.time_since_epoch().count()) + "," +
                           std::to_string(records[1].woke.time_since_epoch().count()) + "," +
                           std::to_string(records[1].stepped.time_since_epoch().count()) + "," +
                           std::to_string(records[1].written.time_since_epoch().count()) + "\n";
  EXPECT_TRUE(csv.ends_with(last)) << csv;
  EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 4);
  EXPECT_FALSE(f.trace.write_csv("/nonexistent/dir/trace.csv"));
}

TEST(StageTrace, OnlyTheFirstWakeOfAStepIsStamped) {
  Fixture f(4);
  f.trace.note_wake();
  f.clock.advance(milliseconds(5));
  f.trace.note_wake();  // a second command before the cycle thread got to the first
  f.trace.begin_step(f.clock.now().mono);
  f.trace.end_step();
  EXPECT_EQ(f.trace.records().front().listener, f.start);
  f.trace.begin_step(f.clock.now().mono);  // woken by nothing stamped: no listener
  f.trace.end_step();
  EXPECT_EQ(f.trace.records().back().listener, Time{});
}

TEST(StageTrace, ATracedCommandStepAllocatesNothing) {
  Fixture f(4);
  const Waker waker = f.runner->waker();
  f.hub.command_step(f.clock.now());  // the hub's first step logs its lifecycle's first transition
  const hubrt::testing::AllocationScope scope;
  for (int i = 0; i < 10; ++i) {
    waker.wake();
    f.trace.begin_step(f.clock.now().mono);
    f.hub.command_step(f.clock.now());
    f.trace.end_step();
  }
  EXPECT_EQ(scope.count(), 0U);
}

}  // namespace
}  // namespace hubrt::runtime
