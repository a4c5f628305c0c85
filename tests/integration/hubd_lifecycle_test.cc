// The lifecycle on the wire: hubd running the Tool ECU on the fake backend, its lift node watched
// through the State's header.lifecycle and through /diagnostics. safe before any command →
// operational on a planner command → safe after the command timeout → fault when the drive trips
// (injected over /sim/fault), held while the move stays in force → operational after a reset.
#include <functional>
#include <optional>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/test_support/hub_under_test.h"

#include "tool_messages.h"

namespace hubrt::integration {
namespace {

using runtime::Lifecycle;
using std::chrono::milliseconds;
using test_support::HubUnderTest;
using test_support::StateStream;
using tool_ecu::LiftCommand;
using tool_ecu::LiftState;
using Diagnostics = diagnostic_msgs_msg_dds__DiagnosticArray_;

// Generous: a busy 2-core machine running sanitizer builds in parallel; diagnostics come at 1 Hz.
constexpr auto kPatience = std::chrono::seconds(20);

std::string joined(const LiftState& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

// The values of the status named `name` in a DiagnosticArray ("tool_ecu: lift", "tool_ecu: cycle").
std::optional<std::string> value_of(const Diagnostics& array, std::string_view name, std::string_view key) {
  for (std::uint32_t i = 0; i < array.status._length; ++i) {
    const auto& status = array.status._buffer[i];
    if (status.name == nullptr || std::string_view(status.name) != name) continue;
    for (std::uint32_t k = 0; k < status.values._length; ++k) {
      const auto& pair = status.values._buffer[k];
      if (pair.key != nullptr && key == pair.key) return std::string(pair.value);
    }
  }
  return std::nullopt;
}

class HubdLifecycleTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/lift/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/tool_ecu/lift/state"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(diagnostics_, "/diagnostics"));
    ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = "tool_ecu"}));
  }

  // The planner: the order of the moment, every 100 ms; none while quiet ("").
  void order(const std::string& action, const std::string& position = "") {
    if (action.empty()) {
      hub_.stop_planner();
      return;
    }
    hub_msgs::LiftCommand command;
    command.set_target_type("lift");
    command.set_target_name("lift");
    command.set_action(action);
    command.set_position(position);
    hub_.plan(*commands_, command.wire(), milliseconds(100));
  }

  // Takes States until `done` holds for one; false after kPatience.
  bool wait_for_state(const std::function<bool(const LiftState&)>& done) {
    return states_->take_until(done, kPatience);
  }
  bool wait_for_lifecycle(Lifecycle wanted) {
    return wait_for_state(
        [wanted](const LiftState& s) { return s.header.lifecycle == static_cast<std::uint8_t>(wanted); });
  }
  bool wait_for_diagnostics(const std::function<bool(const Diagnostics&)>& done) {
    return diagnostics_->take_until(done, kPatience);
  }
  std::string describe() {
    const LiftState& s = states_->latest();
    return fmt::format(
        "last lift State: lifecycle {} ({}), fresh_msg {}, target '{}', moving {}, errors '{}'\nhubd:\n{}",
        s.header.lifecycle, runtime::lifecycle_name(s.header.lifecycle), s.fresh_msg,
        static_cast<const char*>(s.target), s.moving, joined(s), hub_.output());
  }
  void sim_fault(const std::string& fault) { hub_.sim_fault("tool_ecu", "lift_drive", fault); }

  dds::Writer<LiftCommand>* commands_ = nullptr;
  StateStream<LiftState>* states_ = nullptr;
  StateStream<Diagnostics>* diagnostics_ = nullptr;
  HubUnderTest hub_{kPatience};
};

TEST_F(HubdLifecycleTest, SafeOperationalSafeFaultAndBackOnTheWireAndInDiagnostics) {
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kSafe)) << "no command yet: safe\n" << describe();

  order("stop");
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kOperational)) << describe();
  EXPECT_TRUE(states_->latest().fresh_msg);

  order("");  // the planner goes quiet: safe after the command timeout (1 s)
  ASSERT_TRUE(wait_for_state([](const LiftState& s) { return !s.fresh_msg; })) << describe();
  EXPECT_EQ(states_->latest().header.lifecycle, static_cast<std::uint8_t>(Lifecycle::kSafe)) << describe();

  order("move", "work");
  ASSERT_TRUE(wait_for_state([](const LiftState& s) {
    return s.header.lifecycle == static_cast<std::uint8_t>(Lifecycle::kOperational) && s.moving;
  })) << describe();

  ASSERT_NO_FATAL_FAILURE(sim_fault("overcurrent"));
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kFault)) << describe();
  // The move stays in force, yet the lift is held in its safe state: stopped, no target.
  ASSERT_TRUE(wait_for_state([](const LiftState& s) { return s.fault && !s.moving; })) << describe();
  EXPECT_EQ(states_->latest().header.lifecycle, static_cast<std::uint8_t>(Lifecycle::kFault)) << describe();
  EXPECT_TRUE(states_->latest().fresh_msg);
  EXPECT_STREQ(states_->latest().target, "");

  // /diagnostics says so too, per node and for the hub as a whole.
  std::string seen;
  EXPECT_TRUE(wait_for_diagnostics([&](const Diagnostics& a) {
    seen = fmt::format("lift: {} ({}, {} transitions); hub: {}",
                       value_of(a, "tool_ecu: lift", "lifecycle").value_or("-"),
                       value_of(a, "tool_ecu: lift", "lifecycle_reason").value_or("-"),
                       value_of(a, "tool_ecu: lift", "lifecycle_transitions").value_or("-"),
                       value_of(a, "tool_ecu: cycle", "lifecycle").value_or("-"));
    return value_of(a, "tool_ecu: lift", "lifecycle") == "fault" &&
           value_of(a, "tool_ecu: lift", "lifecycle_reason").value_or("").find("lift drive fault") !=
               std::string::npos &&
           value_of(a, "tool_ecu: cycle", "lifecycle") == "fault";
  })) << seen;
  const std::string transitions =
      value_of(diagnostics_->latest(), "tool_ecu: lift", "lifecycle_transitions").value_or("0");
  EXPECT_GE(std::stoi(transitions), 5) << "safe, operational, safe, operational, fault (at least): " << seen;

  order("reset");
  ASSERT_TRUE(wait_for_state([](const LiftState& s) {
    return s.header.lifecycle == static_cast<std::uint8_t>(Lifecycle::kOperational) && s.got_reset &&
           !s.fault;
  })) << describe();
  order("move", "float");
  ASSERT_TRUE(wait_for_state([](const LiftState& s) {
    return s.moving || std::string_view(s.at) == "float";
  })) << "a fresh move acts again\n"
      << describe();
  EXPECT_TRUE(wait_for_diagnostics([&](const Diagnostics& a) {
    return value_of(a, "tool_ecu: lift", "lifecycle") == "operational" &&
           value_of(a, "tool_ecu: lift", "lifecycle_reason") == "command 'reset' in force";
  }));
}

}  // namespace
}  // namespace hubrt::integration
