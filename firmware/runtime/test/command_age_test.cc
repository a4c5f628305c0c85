// A command is as old as its source timestamp says (command_age.h): the judge's verdicts, and a
// node under the manual clock given commands stamped by planners whose clocks are right, 10 s
// behind and 10 s ahead.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr Duration kCommandTimeout = seconds(1);
constexpr Duration kTolerance = milliseconds(50);

WallTime minus(WallTime t, Duration d) {
  return WallTime{t.ns_since_epoch - d.count()};
}

TEST(CommandAgeJudge, JudgesByTheSourceStampAgainstTheHubsWallClock) {
  ManualClock clock;
  CommandAgeJudge judge(kCommandTimeout, kTolerance);
  const Instant now = clock.now();
  const auto judged = [&](Duration age) {
    return judge.judge(CommandTimes{minus(now.wall, age), now, std::nullopt});
  };

  const JudgedAge young = judged(milliseconds(900));
  EXPECT_EQ(young.verdict, AgeVerdict::kYoung);
  EXPECT_EQ(young.written, now.mono - milliseconds(900)) << "freshness counts from the write";
  EXPECT_EQ(judged(kCommandTimeout).verdict, AgeVerdict::kYoung) << "exactly the timeout is still young";
  EXPECT_EQ(judged(kCommandTimeout + milliseconds(1)).verdict, AgeVerdict::kStale);
  EXPECT_EQ(judged(seconds(10)).verdict, AgeVerdict::kStale);

  const JudgedAge slightly_ahead = judged(-milliseconds(30));
  EXPECT_EQ(slightly_ahead.verdict, AgeVerdict::kYoung) << "within the tolerance: age 0";
  EXPECT_EQ(slightly_ahead.written, now.mono);
  EXPECT_EQ(judged(-milliseconds(51)).verdict, AgeVerdict::kFuture);
  EXPECT_EQ(judged(-seconds(10)).verdict, AgeVerdict::kFuture);
  EXPECT_EQ(judge.largest_offset(), seconds(10)) << "the largest offset in magnitude, with its sign";
  EXPECT_EQ(judge.last_offset(), -seconds(10));

  EXPECT_EQ(judge.judge(CommandTimes{WallTime{0}, now, std::nullopt}).verdict, AgeVerdict::kUnstamped)
      << "a sample without a source timestamp cannot be judged";
  EXPECT_EQ(judge.judge(CommandTimes{std::nullopt, now, std::nullopt}).verdict, AgeVerdict::kYoung)
      << "a command built in-process is as old as its arrival";
}

// The cycle reads its clocks, then takes; a thread held between the two (a loaded board, the CI
// kernel VM: 103 ms once) takes commands written after its reading. Judged against the reading the
// source made at the take, such a command is young; against the cycle's, it looked 0.1 s ahead.
TEST(CommandAgeJudge, JudgesAgainstTheHubsWallClockAtTheTakeNotTheCyclesEarlierReading) {
  ManualClock clock;
  CommandAgeJudge judge(kCommandTimeout, kTolerance);
  const Instant cycle = clock.now();
  clock.advance(milliseconds(103));  // the cycle thread is preempted
  const WallTime written = minus(clock.now().wall, milliseconds(1));
  const WallTime take_wall = clock.now().wall;

  EXPECT_EQ(judge.judge(CommandTimes{written, cycle, std::nullopt}).verdict, AgeVerdict::kFuture)
      << "judged against the cycle's reading the command looks 102 ms ahead";
  const JudgedAge at_take = judge.judge(CommandTimes{written, cycle, take_wall});
  EXPECT_EQ(at_take.verdict, AgeVerdict::kYoung);
  EXPECT_EQ(at_take.offset, milliseconds(1));
  EXPECT_EQ(at_take.written, cycle.mono - milliseconds(1))
      << "freshness counts from the cycle's reading minus the age, never from after it";

  // A command 998 ms old at the cycle's reading is 1.101 s old at its take: stale.
  EXPECT_EQ(judge.judge(CommandTimes{minus(cycle.wall, milliseconds(998)), cycle, take_wall}).verdict,
            AgeVerdict::kStale);
  // A stamp ahead of the take by more than the tolerance is still a clock that disagrees.
  EXPECT_EQ(judge.judge(CommandTimes{minus(take_wall, -milliseconds(51)), cycle, take_wall}).verdict,
            AgeVerdict::kFuture);
}

TEST(CommandAgeJudge, UnsyncedClocksJudgeNoAgeButStillDiscardWhatQueuedInAStall) {
  ManualClock clock;
  CommandAgeJudge judge(kCommandTimeout, std::nullopt);
  const Instant now = clock.now();
  EXPECT_EQ(judge.judge(CommandTimes{minus(now.wall, seconds(10)), now, std::nullopt}).verdict,
            AgeVerdict::kYoung);
  EXPECT_EQ(judge.judge(CommandTimes{minus(now.wall, -seconds(10)), now, std::nullopt}).written, now.mono);
  EXPECT_TRUE(judge.offset_seen()) << "the skew is still shown";

  judge.begin_discarding(now.mono + milliseconds(100));
  EXPECT_EQ(judge.judge(CommandTimes{now.wall, now, std::nullopt}).verdict, AgeVerdict::kQueued);
  clock.advance(milliseconds(100));
  EXPECT_EQ(judge.judge(CommandTimes{clock.now().wall, clock.now(), std::nullopt}).verdict,
            AgeVerdict::kYoung)
      << "a command taken once the hub caught up acts";
}

class CommandAgeNodeTest : public ::testing::Test {
 protected:
  void make_node(ClockTolerance tolerance) {
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = kCommandTimeout;
    options.clock_tolerance = tolerance;
    node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  }
  // A planner whose clock is `skew` off the hub's sends "open", written `age` ago by its clock.
  void send_open(Duration age, Duration skew = Duration::zero()) {
    OwnedValveCommand open;
    source_.push(open, WallTime{clock_.now().wall.ns_since_epoch - age.count() + skew.count()});
  }
  void step() { node_->step(clock_.now()); }
  [[nodiscard]] const ValveState& state() const { return node_->state().wire(); }
  [[nodiscard]] bool error_has(const std::string& fragment) const {
    for (std::uint32_t i = 0; i < state().error_list._length; ++i) {
      if (std::string(state().error_list._buffer[i]).find(fragment) != std::string::npos) return true;
    }
    return false;
  }

  ManualClock clock_;
  ValveWorld world_;
  QueueSource source_;
  CountingSink sink_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::unique_ptr<Node<ValveLogic>> node_;
};

TEST_F(CommandAgeNodeTest, ACommandThatWaitedLeavesOnlyTheRestOfItsFreshness) {
  make_node(kTolerance);
  send_open(milliseconds(900));  // waited 0.9 s in a socket
  step();
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kOperational);
  EXPECT_TRUE(world_.open);
  EXPECT_TRUE(state().fresh_msg);
  EXPECT_NEAR(state().t_plus, 0.9, 1e-6) << "t_plus counts from the write, not the arrival";

  clock_.advance(milliseconds(100));
  step();
  EXPECT_TRUE(state().fresh_msg) << "exactly the timeout after the write";
  clock_.advance(milliseconds(1));
  step();
  EXPECT_FALSE(state().fresh_msg) << "0.1 s of freshness was left, not 1 s";
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kSafe);
  EXPECT_FALSE(world_.open);
}

TEST_F(CommandAgeNodeTest, APlannerTenSecondsBehindNeverActs) {
  make_node(kTolerance);
  for (int i = 0; i < 30; ++i) {  // 3 s of commands at 10 Hz, each stamped 10 s in the past
    send_open(milliseconds(0), -seconds(10));
    step();
    EXPECT_NE(node_->lifecycle().state(), Lifecycle::kOperational) << "command " << i;
    EXPECT_FALSE(world_.open) << "command " << i;
    EXPECT_FALSE(state().fresh_msg) << "command " << i;
    clock_.advance(milliseconds(100));
  }
  EXPECT_EQ(world_.updates_with_command, 0);
  EXPECT_EQ(node_->commands_stale(), 30u);
  EXPECT_EQ(node_->rejected(), 0u) << "stale is not invalid";
  EXPECT_TRUE(error_has("stale command: written 10.000 s ago, older than the command timeout"));
  ASSERT_NE(node_->command_ages(), nullptr);
  EXPECT_EQ(node_->command_ages()->largest_offset(), seconds(10)) << "the skew /diagnostics shows";
}

TEST_F(CommandAgeNodeTest, APlannerTenSecondsAheadIsRejectedWithTheReason) {
  make_node(kTolerance);
  send_open(milliseconds(0), seconds(10));
  step();
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kSafe);
  EXPECT_FALSE(world_.open);
  EXPECT_FALSE(state().fresh_msg);
  EXPECT_EQ(node_->rejected(), 1u);
  EXPECT_TRUE(
      error_has("rejected command: stamped 10.000 s in the future, beyond the clock tolerance (50 ms)"));
  EXPECT_EQ(node_->command_ages()->last_offset(), -seconds(10));

  // Within the tolerance ahead, the command acts (as written now).
  send_open(milliseconds(0), milliseconds(40));
  step();
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kOperational);
  EXPECT_TRUE(world_.open);
}

TEST_F(CommandAgeNodeTest, ACommandWrittenWhileTheCycleWasHeldActsAsJustWritten) {
  make_node(kTolerance);
  const Instant cycle = clock_.now();
  clock_.advance(milliseconds(103));  // held between the cycle's reading and the take
  OwnedValveCommand open;
  source_.push(open, clock_.now().wall, clock_.now().wall);
  node_->step(cycle);
  EXPECT_EQ(node_->rejected(), 0u);
  EXPECT_FALSE(error_has("future")) << "no clock disagreement reported";
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kOperational);
  EXPECT_TRUE(world_.open);
  EXPECT_TRUE(state().fresh_msg);
  EXPECT_FLOAT_EQ(state().t_plus, 0.0f);
}

TEST_F(CommandAgeNodeTest, WithUnsyncedClocksSkewedPlannersActAsOnArrival) {
  make_node(std::nullopt);
  send_open(milliseconds(0), -seconds(10));
  step();
  EXPECT_EQ(node_->lifecycle().state(), Lifecycle::kOperational) << "clock_tolerance_ms: none judges no age";
  EXPECT_TRUE(state().fresh_msg);
  EXPECT_FLOAT_EQ(state().t_plus, 0.0f);
  clock_.advance(kCommandTimeout + milliseconds(1));
  step();
  EXPECT_FALSE(state().fresh_msg) << "the watchdog counts from the arrival then";
  EXPECT_EQ(node_->commands_stale(), 0u);
}

// Every command a node takes reaches the observer with its source and arrival times.
TEST_F(CommandAgeNodeTest, TheObserverSeesEachCommandsTimesAndOutcome) {
  struct Seen {
    CommandTimes times;
    CommandOutcome outcome;
  };
  class Recorder final : public CommandObserver {
   public:
    void on_command(std::string_view /*node*/, const void* /*command*/, const CommandTimes& times,
                    CommandOutcome outcome) noexcept override {
      seen.push_back(Seen{times, outcome});
    }
    std::vector<Seen> seen;
  } recorder;
  recorder.seen.reserve(8);
  NodeOptions options;
  options.name = "v1";
  options.command_timeout = kCommandTimeout;
  options.command_observer = &recorder;
  node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  send_open(milliseconds(200));
  send_open(milliseconds(100));
  send_open(seconds(5));
  send_open(milliseconds(0), seconds(5));
  step();
  ASSERT_EQ(recorder.seen.size(), 4u);
  EXPECT_EQ(recorder.seen[0].outcome, CommandOutcome::kTookEffect);
  EXPECT_EQ(recorder.seen[1].outcome, CommandOutcome::kRepeat);
  EXPECT_EQ(recorder.seen[2].outcome, CommandOutcome::kStale);
  EXPECT_EQ(recorder.seen[3].outcome, CommandOutcome::kRejected);
  const Instant now = clock_.now();
  EXPECT_EQ(recorder.seen[0].times.taken.mono, now.mono);
  ASSERT_TRUE(recorder.seen[0].times.source.has_value());
  EXPECT_EQ(recorder.seen[0].times.source->ns_since_epoch,
            now.wall.ns_since_epoch - Duration(milliseconds(200)).count());
}

}  // namespace
}  // namespace hubrt::runtime::testing
