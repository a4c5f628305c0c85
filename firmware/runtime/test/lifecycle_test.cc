// The lifecycle of a node and of a hub (lifecycle.h) under a manual clock: which state each
// situation leads to, the reason and count of every transition, one log line per transition, the
// State's header.lifecycle — and that the logic is handed the command in force only while the
// node is operational.
#include "hubrt/runtime/lifecycle.h"

#include <cctype>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>

#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <spdlog/sinks/ostream_sink.h>

#include "hubrt/runtime/hub.h"
#include "hubrt/runtime/node.h"
#include "hubrt/runtime/reflected_message_ops.h"

#include "hub_msgs_common.h"
#include "node_test_support.h"
#include "valve_test_reflect.h"

namespace hubrt::runtime::testing {
namespace {

using std::chrono::milliseconds;
using ::testing::HasSubstr;

constexpr Duration kTimeout = milliseconds(500);
constexpr Duration kPeriod = milliseconds(100);

std::size_t count_of(const std::string& text, const std::string& fragment) {
  std::size_t n = 0;
  for (auto at = text.find(fragment); at != std::string::npos; at = text.find(fragment, at + 1)) ++n;
  return n;
}

OwnedValveCommand command(std::string action, std::string target = "v1") {
  OwnedValveCommand c;
  c.action = std::move(action);
  c.target_name = std::move(target);
  return c;
}

class NodeLifecycleTest : public ::testing::Test {
 protected:
  NodeLifecycleTest()
      : log_(std::make_shared<spdlog::logger>("test",
                                              std::make_shared<spdlog::sinks::ostream_sink_mt>(text_))) {
    NodeOptions options;
    options.name = "v1";
    options.command_timeout = kTimeout;
    options.log = log_;
    node_ = std::make_unique<Node<ValveLogic>>(options, ValveLogic(world_), source_, sink_, ops_);
  }

  // One cycle: the planner sends `action` (empty: nothing), then the node steps. After every step
  // the logic must have been given a command exactly when the node is operational, and the
  // valve is open only then.
  void cycle(const std::string& action = "") {
    if (!action.empty()) source_.push(command(action));
    clock_.advance(kPeriod);
    node_->step(clock_.now());
    const bool operational = state() == Lifecycle::kOperational;
    EXPECT_EQ(world_.last_update_with_command, operational) << "in state " << lifecycle_name(state());
    if (!operational) {
      EXPECT_FALSE(world_.open) << "outputs not safe in state " << lifecycle_name(state());
    }
    EXPECT_EQ(node_->state().header().lifecycle(), static_cast<std::uint8_t>(state()));
  }
  [[nodiscard]] Lifecycle state() const { return node_->lifecycle().state(); }
  [[nodiscard]] std::string reason() const { return std::string(node_->lifecycle().reason()); }
  [[nodiscard]] std::string log() const { return text_.str(); }

  ManualClock clock_;
  ValveWorld world_;
  QueueSource source_;
  CountingSink sink_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::ostringstream text_;
  std::shared_ptr<spdlog::logger> log_;
  std::unique_ptr<Node<ValveLogic>> node_;
};

TEST_F(NodeLifecycleTest, SafeUntilTheFirstCommandThenOperationalThenSafeAfterTheTimeout) {
  EXPECT_EQ(state(), Lifecycle::kOpeningDevices) << "a node is created with its devices opened";
  EXPECT_EQ(node_->lifecycle().transitions(), 0u);

  cycle();
  EXPECT_EQ(state(), Lifecycle::kSafe);
  EXPECT_EQ(reason(), "no command received yet");
  cycle();
  EXPECT_EQ(node_->lifecycle().transitions(), 1u) << "staying in a state is no transition";

  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kOperational);
  EXPECT_EQ(reason(), "command 'open' in force");
  EXPECT_TRUE(world_.open);
  cycle("close");
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kOperational);
  EXPECT_EQ(reason(), "command 'open' in force") << "a new command in force is no transition";
  EXPECT_EQ(node_->lifecycle().transitions(), 2u);

  // The planner goes quiet: the node stays operational up to the timeout, then goes safe.
  for (int i = 0; i < 5; ++i) cycle();
  EXPECT_EQ(state(), Lifecycle::kOperational) << "500 ms of silence is within the timeout";
  cycle();
  EXPECT_EQ(state(), Lifecycle::kSafe);
  EXPECT_THAT(reason(), HasSubstr("command timeout: no valid command for more than 0.500 s"));
  EXPECT_EQ(node_->lifecycle().previous(), Lifecycle::kOperational);
  EXPECT_EQ(node_->lifecycle().transitions(), 3u);

  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kOperational) << "a fresh command after the timeout";
  EXPECT_TRUE(world_.open);

  EXPECT_EQ(count_of(log(), "v1: lifecycle opening_devices -> safe (transition 1): no command received yet"),
            1u)
      << log();
  EXPECT_EQ(count_of(log(), "v1: lifecycle safe -> operational"), 2u) << log();
  EXPECT_EQ(count_of(log(), "v1: lifecycle operational -> safe (transition 3): command timeout"), 1u)
      << log();
}

TEST_F(NodeLifecycleTest, ALatchedFaultHoldsTheNodeSafeUntilAResetWhileTheCommandStaysInForce) {
  cycle("open");
  ASSERT_EQ(state(), Lifecycle::kOperational);

  world_.overpressure_input = true;
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kFault);
  EXPECT_EQ(reason(), "latched fault, send reset to clear: overpressure: valve held closed until reset")
      << "the reason names the logic's first error";
  EXPECT_TRUE(node_->state().fresh_msg()) << "the command is in force, yet the logic does not get it";

  world_.overpressure_input = false;
  for (int i = 0; i < 3; ++i) cycle("open");
  EXPECT_EQ(state(), Lifecycle::kFault) << "latched: the cause going away is not enough";

  // A fault outranks safe: a planner that went quiet comes back to a node that asks for a reset.
  for (int i = 0; i < 7; ++i) cycle();
  EXPECT_FALSE(node_->state().fresh_msg());
  EXPECT_EQ(state(), Lifecycle::kFault);

  world_.overpressure_input = true;
  cycle("reset");
  EXPECT_EQ(state(), Lifecycle::kFault) << "a reset while the cause is still there latches it again";
  EXPECT_EQ(world_.resets, 1);

  world_.overpressure_input = false;
  cycle("open");
  cycle("reset");
  EXPECT_EQ(state(), Lifecycle::kOperational);
  EXPECT_EQ(reason(), "command 'reset' in force");
  cycle("open");
  EXPECT_TRUE(world_.open);
  EXPECT_EQ(count_of(log(), "-> fault"), 1u) << log();
}

TEST_F(NodeLifecycleTest, RecoveringWhileADeviceIsMissingThenBackToTheCommandInForce) {
  cycle("open");
  world_.device_missing = true;
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kRecovering);
  EXPECT_EQ(reason(), "a device the node needs is not open, retrying: valve device not available");
  cycle("open");
  world_.device_missing = false;
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kOperational);
  EXPECT_TRUE(world_.open);

  // Missing with no command in force: still recovering (what is wrong outranks "no command").
  world_.device_missing = true;
  for (int i = 0; i < 7; ++i) cycle();
  EXPECT_EQ(state(), Lifecycle::kRecovering);
  world_.device_missing = false;
  cycle();
  EXPECT_EQ(state(), Lifecycle::kSafe);
  EXPECT_THAT(reason(), HasSubstr("command timeout"));

  // A latched fault outranks a missing device.
  world_.device_missing = true;
  world_.overpressure_input = true;
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kFault);
}

TEST_F(NodeLifecycleTest, TheHubStoppingDrivesTheNodeSafeForGood) {
  cycle("open");
  ASSERT_TRUE(world_.open);
  node_->enter_safe_state();
  EXPECT_EQ(state(), Lifecycle::kSafe);
  EXPECT_EQ(reason(), "hub stopping: outputs driven safe");
  EXPECT_FALSE(world_.open);
  EXPECT_EQ(node_->state().header().lifecycle(), static_cast<std::uint8_t>(Lifecycle::kSafe));
  cycle("open");
  EXPECT_EQ(state(), Lifecycle::kSafe) << "a command after the stop must not actuate";
  EXPECT_EQ(count_of(log(), "v1: lifecycle operational -> safe (transition 2): hub stopping"), 1u) << log();
}

// Every State published carries the state in its header.
TEST_F(NodeLifecycleTest, ThePublishedHeaderCarriesTheLifecycle) {
  cycle();
  ASSERT_TRUE(node_->publish(clock_.now()).is_ok());
  EXPECT_EQ(node_->state().header().lifecycle(), 2u);  // LIFECYCLE_SAFE
  cycle("open");
  ASSERT_TRUE(node_->publish(clock_.now()).is_ok());
  EXPECT_EQ(node_->state().header().lifecycle(), 3u);  // LIFECYCLE_OPERATIONAL
}

// The ROS 2 interface names the same numbers: LIFECYCLE_<NAME>=<number> for every state.
TEST(LifecycleName, MatchesTheConstantsOfStateHeaderMsg) {
  std::ifstream msg(std::string(HUBRT_SOURCE_DIR) + "/firmware/msgs/msg/StateHeader.msg");
  ASSERT_TRUE(msg.good());
  const std::regex constant(R"(^uint8 LIFECYCLE_([A-Z_]+)=([0-9]+)\b)");
  std::size_t seen = 0;
  for (std::string line; std::getline(msg, line);) {
    std::smatch m;
    if (!std::regex_search(line, m, constant)) continue;
    std::string name = m[1].str();
    for (char& c : name) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    EXPECT_EQ(lifecycle_name(static_cast<std::uint8_t>(std::stoi(m[2].str()))), name) << line;
    ++seen;
  }
  EXPECT_EQ(seen, 7u) << "one constant per state";
}

// The same numbers as the constants of the IDL generated from StateHeader.msg (module
// StateHeader_Constants: idlc's #defines), so C code and tools built from the IDL agree too.
TEST(LifecycleName, TheGeneratedStateHeaderConstantsAreTheLifecycleValues) {
  const auto value = [](Lifecycle l) { return static_cast<int>(l); };
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_CONFIGURING, value(Lifecycle::kConfiguring));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_OPENING_DEVICES,
            value(Lifecycle::kOpeningDevices));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_SAFE, value(Lifecycle::kSafe));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_OPERATIONAL, value(Lifecycle::kOperational));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_FAULT, value(Lifecycle::kFault));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_RECOVERING, value(Lifecycle::kRecovering));
  EXPECT_EQ(hub_msgs_msg_dds__StateHeader_Constants_LIFECYCLE_STOPPING, value(Lifecycle::kStopping));
}

TEST(LifecycleName, NamesEveryWireValueAndUnknownBeyond) {
  EXPECT_EQ(lifecycle_name(Lifecycle::kOpeningDevices), "opening_devices");
  EXPECT_EQ(lifecycle_name(std::uint8_t{4}), "fault");
  EXPECT_EQ(lifecycle_name(std::uint8_t{7}), "unknown");
  EXPECT_EQ(lifecycle_name(std::uint8_t{255}), "unknown");
}

// The hub: its phases, then the worst of its nodes.
class HubLifecycleTest : public ::testing::Test {
 protected:
  struct Valve {
    ValveWorld world;
    QueueSource source;
    CountingSink sink;
  };

  HubLifecycleTest() {
    HubOptions options;
    options.type = "valves";
    options.name = "h1";
    options.period = kPeriod;
    options.log =
        std::make_shared<spdlog::logger>("test", std::make_shared<spdlog::sinks::ostream_sink_mt>(text_));
    hub_ = std::make_unique<Hub>(options);
  }
  void add(Valve& valve, const std::string& name) {
    NodeOptions options;
    options.name = name;
    options.command_timeout = kTimeout;
    options.log = hub_->options().log;
    hub_->add_node(
        std::make_unique<Node<ValveLogic>>(options, ValveLogic(valve.world), valve.source, valve.sink, ops_));
  }
  void cycle() {
    clock_.advance(kPeriod);
    hub_->cycle(clock_.now());
  }
  [[nodiscard]] Lifecycle state() const { return hub_->lifecycle().state(); }

  ManualClock clock_;
  std::ostringstream text_;
  ReflectedMessageOps ops_{msgs::type_info_of<ValveCommand>()};
  std::unique_ptr<Hub> hub_;
  Valve a_;
  Valve b_;
};

TEST_F(HubLifecycleTest, PhasesThenTheWorstOfItsNodes) {
  EXPECT_EQ(state(), Lifecycle::kConfiguring);
  hub_->begin_opening_devices();
  EXPECT_EQ(state(), Lifecycle::kOpeningDevices);
  add(a_, "a");
  add(b_, "b");

  cycle();
  EXPECT_EQ(state(), Lifecycle::kSafe);
  EXPECT_EQ(std::string(hub_->lifecycle().reason()), "node 'a' safe: no command received yet");

  a_.source.push(command("open", "a"));
  cycle();
  EXPECT_EQ(state(), Lifecycle::kSafe) << "b has no command yet";
  b_.source.push(command("open", "b"));
  cycle();
  EXPECT_EQ(state(), Lifecycle::kOperational);
  EXPECT_EQ(std::string(hub_->lifecycle().reason()), "every node operational");

  b_.world.device_missing = true;
  cycle();
  EXPECT_EQ(state(), Lifecycle::kRecovering);
  a_.world.overpressure_input = true;
  cycle();
  EXPECT_EQ(state(), Lifecycle::kFault) << "fault is worse than recovering";
  EXPECT_THAT(std::string(hub_->lifecycle().reason()), HasSubstr("node 'a' fault: latched fault"));

  hub_->enter_safe_state();
  EXPECT_EQ(state(), Lifecycle::kStopping);
  cycle();
  EXPECT_EQ(state(), Lifecycle::kStopping) << "a stopping hub stays stopping";
  for (const auto& node : hub_->nodes()) EXPECT_EQ(node->lifecycle().state(), Lifecycle::kSafe);
  EXPECT_FALSE(a_.world.open);
  EXPECT_FALSE(b_.world.open);
  EXPECT_EQ(hub_->lifecycle().transitions(), 6u);
  EXPECT_EQ(count_of(text_.str(), "hub 'h1': lifecycle"), 6u) << text_.str();
}

}  // namespace
}  // namespace hubrt::runtime::testing
