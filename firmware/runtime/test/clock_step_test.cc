// A wall clock that steps by 10 s — on the hub or on the planner, forward or back — while a
// planner commands at 10 Hz, under the manual clock: the node follows the commands until the step,
// then none acts any more (they look 10 s old: stale; or 10 s ahead: rejected, the reason in
// error_list), and the node goes safe one command timeout after the last good command was
// written, at most one period later. The monotonic clock never steps, and the command in force
// keeps exactly its freshness. Each case writes its row of docs/safety.md's time-to-safe table.
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"
#include "hubrt/test_support/time_to_safe.h"

#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

constexpr Duration kTimeout = seconds(1);
constexpr Duration kHubPeriod = milliseconds(10);  // the hub's cycle (100 Hz)
constexpr Duration kStep = seconds(10);

struct Step {
  const char* name;
  bool on_hub;         // the hub's wall clock steps (else the planner's)
  Duration by;         // by how much
  const char* reason;  // what error_list says of the commands after the step
};

class ClockStepTest : public ::testing::TestWithParam<Step> {
 protected:
  ClockStepTest() {
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = kTimeout;
    node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  }
  // The hub's clocks now: the manual clock, its wall stepped when the hub's clock stepped.
  Instant hub_now() const {
    Instant now = clock_.now();
    now.wall.ns_since_epoch += hub_offset_.count();
    return now;
  }

  ManualClock clock_;
  Duration hub_offset_{0};
  Duration planner_offset_{0};
  ValveWorld world_;
  QueueSource source_;
  CountingSink sink_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::unique_ptr<Node<ValveLogic>> node_;
};

TEST_P(ClockStepTest, NoCommandActsAfterTheStepAndTheNodeGoesSafeOnItsTimeout) {
  const Step& step = GetParam();
  const Time start = clock_.now().mono;
  const Time stepped_at = start + seconds(2);
  std::optional<Time> safe_at;
  for (Time planner_next = start; clock_.now().mono < start + seconds(5); clock_.advance(kHubPeriod)) {
    const Time now = clock_.now().mono;
    if (now >= stepped_at && hub_offset_ == Duration::zero() && planner_offset_ == Duration::zero()) {
      (step.on_hub ? hub_offset_ : planner_offset_) = step.by;
    }
    if (now >= planner_next) {  // the planner writes "open" by its own clock (the hub's, plus its skew)
      source_.push(OwnedValveCommand{}, WallTime{clock_.now().wall.ns_since_epoch + planner_offset_.count()});
      planner_next += milliseconds(100);
    }
    node_->step(hub_now());
    const bool operational = node_->lifecycle().state() == Lifecycle::kOperational;
    if (now < stepped_at) {
      ASSERT_TRUE(operational) << "before the step, at " << to_seconds(now - start) << " s";
    } else if (!operational && !safe_at) {
      safe_at = now;
    } else if (operational && safe_at) {
      FAIL() << "operational again after the step, at " << to_seconds(now - start) << " s";
    }
  }
  ASSERT_TRUE(safe_at.has_value()) << "never went safe";
  EXPECT_FALSE(world_.open);
  EXPECT_FALSE(node_->state().wire().fresh_msg);
  EXPECT_TRUE(node_->errors().contains(step.reason)) << node_->errors().at(0);
  // The last good command was written at most one planner period before the step.
  const Duration to_safe = *safe_at - stepped_at;
  EXPECT_LE(to_safe, kTimeout + kHubPeriod);
  EXPECT_GE(to_safe, kTimeout - milliseconds(100));
  test_support::record_time_to_safe(
      std::string("clock_step_") + step.name,
      test_support::TimeToSafe{std::string(step.on_hub ? "the hub's" : "the planner's") +
                                   " wall clock steps " + (step.by > Duration::zero() ? "forward" : "back") +
                                   " 10 s",
                               "any (the runtime's command intake)", "every output (node safe)",
                               std::string("commands judged by their source timestamps: ") +
                                   (std::string(step.reason).find("stale") != std::string::npos
                                        ? "they look 10 s old (stale)"
                                        : "they look 10 s ahead (rejected)") +
                                   "; the command in force lapses on the monotonic clock",
                               to_seconds(to_safe), to_seconds(kTimeout + kHubPeriod),
                               "command timeout + one period (manual clock)", "hubrt_clock_step_test"});
}

INSTANTIATE_TEST_SUITE_P(
    Steps, ClockStepTest,
    ::testing::Values(Step{"hub_forward", true, kStep, "stale command: written 10."},
                      Step{"hub_back", true, -kStep, "rejected command: stamped 10."},
                      Step{"planner_forward", false, kStep, "rejected command: stamped 10."},
                      Step{"planner_back", false, -kStep, "stale command: written 10."}),
    [](const ::testing::TestParamInfo<Step>& param) { return std::string(param.param.name); });

}  // namespace
}  // namespace hubrt::runtime::testing
