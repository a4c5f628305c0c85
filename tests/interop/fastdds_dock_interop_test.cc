// A ROS 2-vendor planner against hubd: eProsima Fast DDS (ROS 2's default RMW) with type support
// generated from the .msg files of ros2/hub_msgs discovers a Dock ECU hubd (Cyclone DDS) over
// loopback, reads its States and commands it (issue 13 point 3; docs/interop.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/test_support/hub_process.h"

#include "fastdds_dock_planner.h"

namespace hubrt::interop {
namespace {

using hub_msgs::msg::DockState;
using std::chrono::duration_cast;
using std::chrono::milliseconds;
using std::chrono::seconds;
namespace lifecycle = hub_msgs::msg::StateHeader_Constants;

// hubs/dock_ecu/dock_ecu.yaml, the hub the test starts: State heartbeat and command timeout.
constexpr double kHeartbeatPeriodS = 0.1;             // rate_hz: 10
constexpr auto kCommandTimeout = milliseconds(1000);  // command_timeout_ms: 1000

double stamp_seconds(const DockState& state) {
  return state.header().stamp().sec() + state.header().stamp().nanosec() * 1e-9;
}

class FastDdsDockInteropTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire_outside_ephemeral_ports();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto planner = FastDdsDockPlanner::create(domain_->domain_id(), DockNodeTypes::kCommandTopic,
                                              DockNodeTypes::kStateTopic);
    ASSERT_TRUE(planner) << planner.error().message;
    planner_ = std::move(*planner);
    test_support::HubProcessOptions options;  // the Dock ECU on the host-sim board (fake HAL)
    auto hub = test_support::HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(planner_->wait_for_hub(kPatience)) << planner_->match_report() << "\n" << hub_->output();
  }
  void TearDown() override {
    if (planner_) (void)planner_->stop_repeating();
  }

  std::optional<DockState> state_where(const std::function<bool(const DockState&)>& predicate) {
    auto received = planner_->wait_for_state(predicate, kPatience);
    if (!received) return std::nullopt;
    return received->state;
  }

  std::optional<test_support::TestDomain> domain_;
  std::unique_ptr<FastDdsDockPlanner> planner_;
  std::optional<test_support::HubProcess> hub_;
};

TEST_F(FastDdsDockInteropTest, ReadsTheHeartbeatAtTheConfiguredRateWithSequenceUpByOne) {
  auto first = planner_->next_state(kPatience);
  ASSERT_TRUE(first) << "no State reached Fast DDS; " << planner_->match_report() << "\n" << hub_->output();
  EXPECT_EQ(first->state.name(), "dock");
  EXPECT_FALSE(first->state.fresh_msg()) << "no command was sent";
  EXPECT_EQ(first->state.header().lifecycle(), lifecycle::LIFECYCLE_SAFE);
  ASSERT_EQ(first->state.slots().size(), 4u) << "the four slots of dock_ecu.yaml";
  EXPECT_EQ(first->state.slots()[0].name(), "ladder_frame_tool");

  constexpr int kStates = 30;  // 3 s of heartbeat
  ReceivedState previous = *first;
  for (int i = 1; i < kStates; ++i) {
    auto next = planner_->next_state(kPatience);
    ASSERT_TRUE(next) << "the heartbeat stopped after " << i << " States\n" << hub_->output();
    ASSERT_EQ(next->state.header().seq(), previous.state.header().seq() + 1)
        << "a State lost or repeated on loopback (reliable, keep last 10)";
    previous = *next;
  }
  // The hub's own stamps judge its cycle (no command: only the heartbeat publishes). hubd keeps
  // deadline k = start + k * period without catch-up, so a stalled cycle stretches the mean
  // but cannot shrink it: the lower bound is tight, the upper one allows a loaded machine's stalls.
  const double mean_period = (stamp_seconds(previous.state) - stamp_seconds(first->state)) / (kStates - 1);
  EXPECT_GE(mean_period, kHeartbeatPeriodS * 0.9);
  EXPECT_LE(mean_period, kHeartbeatPeriodS * 1.5);
  // As received by Fast DDS (its own clock): the same rate within the same slack, judged over
  // the whole run so that one late delivery does not count twice.
  const double received_over = std::chrono::duration<double>(previous.received - first->received).count();
  std::printf("heartbeat through Fast DDS: mean period %.1f ms by the hub's stamps, %.1f ms as received\n",
              mean_period * 1e3, received_over / (kStates - 1) * 1e3);
  EXPECT_GE(received_over, (kStates - 1) * kHeartbeatPeriodS * 0.8);
  EXPECT_LE(received_over, (kStates - 1) * kHeartbeatPeriodS * 1.5);
}

TEST_F(FastDdsDockInteropTest, ACommandIsEchoedFreshAndTheWatchdogMakesTheNodeSafeWhenCommandsStop) {
  planner_->start_repeating(dock_command("dock", "dock", "monitor"), kCommandPeriod);
  auto operational = state_where([](const DockState& s) { return s.fresh_msg(); });
  ASSERT_TRUE(operational) << "the command did not take effect\n" << hub_->output();
  EXPECT_EQ(operational->echo().target_type(), "dock");
  EXPECT_EQ(operational->echo().target_name(), "dock");
  EXPECT_EQ(operational->echo().action(), "monitor");
  EXPECT_EQ(operational->header().lifecycle(), lifecycle::LIFECYCLE_OPERATIONAL);
  EXPECT_TRUE(operational->error_list().empty()) << joined_errors(*operational);
  EXPECT_FALSE(operational->got_reset());

  // The planner goes quiet: fresh_msg falls, the node goes safe and says why — not before the
  // timeout has passed since the last command written.
  const auto last_write = planner_->stop_repeating();
  auto timed_out = planner_->wait_for_state([](const DockState& s) { return !s.fresh_msg(); }, kPatience);
  ASSERT_TRUE(timed_out) << "fresh_msg stayed true without commands\n" << hub_->output();
  const auto silent_for = duration_cast<milliseconds>(timed_out->received - last_write);
  EXPECT_GE(silent_for, kCommandTimeout) << "the watchdog tripped early";
  EXPECT_LE(silent_for, kCommandTimeout + seconds(5)) << "loaded machine allowance exceeded";
  EXPECT_EQ(timed_out->state.header().lifecycle(), lifecycle::LIFECYCLE_SAFE);
  EXPECT_NE(joined_errors(timed_out->state).find("command timeout"), std::string::npos)
      << joined_errors(timed_out->state);
  EXPECT_EQ(timed_out->state.echo().action(), "monitor") << "the echo keeps the last command";
}

TEST_F(FastDdsDockInteropTest, BadCommandsAreRejectedInTheErrorListAndTakeNoEffect) {
  struct Case {
    hub_msgs::msg::DockCommand command;
    std::string rejection;
  };
  const Case cases[] = {
      {dock_command("dock", "dock", "explode"),
       "rejected command: unknown action 'explode' (expected one of: monitor, reset)"},
      {dock_command("lift", "dock", "monitor"), "wrong target type 'lift' for node 'dock' of type 'dock'"},
  };
  for (const Case& c : cases) {
    planner_->start_repeating(c.command, kCommandPeriod);
    auto rejected = state_where(
        [&c](const DockState& s) { return joined_errors(s).find(c.rejection) != std::string::npos; });
    (void)planner_->stop_repeating();
    ASSERT_TRUE(rejected) << "no rejection '" << c.rejection << "'\n" << hub_->output();
    EXPECT_FALSE(rejected->fresh_msg()) << c.rejection;
    EXPECT_NE(rejected->header().lifecycle(), lifecycle::LIFECYCLE_OPERATIONAL) << c.rejection;
  }
}

// In the node-type layout every node of a type shares /<type>/command and takes only what names
// it (firmware/runtime node.h, addressed_here): a command for another node is not this node's
// business — no effect, and no rejection either.
TEST_F(FastDdsDockInteropTest, ACommandForAnotherNodeOfTheTypeTakesNoEffect) {
  planner_->start_repeating(dock_command("dock", "dock9", "monitor"), kCommandPeriod);
  ASSERT_TRUE(planner_->next_state(kPatience)) << hub_->output();
  planner_->drain();
  constexpr int kStates = 15;  // 1.5 s of heartbeat with the command arriving every 50 ms
  for (int i = 0; i < kStates; ++i) {
    auto received = planner_->next_state(kPatience);
    ASSERT_TRUE(received) << hub_->output();
    EXPECT_FALSE(received->state.fresh_msg());
    EXPECT_NE(received->state.echo().target_name(), "dock9");
    EXPECT_EQ(joined_errors(received->state).find("dock9"), std::string::npos)
        << joined_errors(received->state);
    EXPECT_EQ(received->state.header().lifecycle(), lifecycle::LIFECYCLE_SAFE);
  }
}

// The other direction's reader is Cyclone again: hubctl (its own process) sees the State the hub
// wrote in answer to the Fast DDS command, so one vendor's command and another vendor's reader
// meet in one State.
TEST_F(FastDdsDockInteropTest, ACycloneReaderSeesTheHubAnsweringTheFastDdsCommand) {
  planner_->start_repeating(dock_command("fastdds_probe", "dock", "monitor"), kCommandPeriod);
  ASSERT_TRUE(state_where([](const DockState& s) {
    return joined_errors(s).find("fastdds_probe") != std::string::npos;
  })) << hub_->output();
  auto hubctl = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH, {"echo", "/dock_ecu/dock/state", "--json", "--count", "5", "--timeout", "20"},
      domain_->env());
  ASSERT_TRUE(hubctl) << hubctl.error().message;
  auto status = hubctl->wait(seconds(60));
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hubctl->stderr_text();
  EXPECT_NE(hubctl->stdout_text().find("wrong target type 'fastdds_probe' for node 'dock'"),
            std::string::npos)
      << hubctl->stdout_text() << hubctl->stderr_text();
}

}  // namespace
}  // namespace hubrt::interop
