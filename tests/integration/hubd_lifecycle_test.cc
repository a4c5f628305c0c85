// The lifecycle on the wire: hubd running the Tool ECU on the fake backend, its lift node watched
// through the State's header.lifecycle and through /diagnostics. safe before any command →
// operational on a planner command → safe after the command timeout → fault when the drive trips
// (injected over /sim/fault), held while the move stays in force → operational after a reset.
#include <atomic>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/runtime/lifecycle.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "hub_process.h"
#include "tool_messages.h"

namespace hubrt::integration {
namespace {

using runtime::Lifecycle;
using std::chrono::milliseconds;
using tool_ecu::LiftCommand;
using tool_ecu::LiftState;
using Diagnostics = diagnostic_msgs_msg_dds__DiagnosticArray_;

// Generous: a busy 2-core machine running sanitizer builds in parallel; diagnostics come at 1 Hz.
constexpr auto kPatience = std::chrono::seconds(20);

char* wire(const std::string& text) {
  return const_cast<char*>(text.c_str());  // NOLINT: the wire type wants char*
}

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
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    command_topic_.emplace(*dds::Topic<LiftCommand>::create(*participant_, "/lift/command"));
    command_writer_.emplace(*dds::Writer<LiftCommand>::create(*participant_, *command_topic_));
    state_topic_.emplace(*dds::Topic<LiftState>::create(*participant_, "/tool_ecu/lift/state"));
    state_reader_.emplace(*dds::Reader<LiftState>::create(*participant_, *state_topic_));
    diagnostics_topic_.emplace(*dds::Topic<Diagnostics>::create(*participant_, "/diagnostics"));
    diagnostics_reader_.emplace(*dds::Reader<Diagnostics>::create(*participant_, *diagnostics_topic_));
    fault_topic_.emplace(
        *dds::Topic<hub_msgs_msg_dds__SimFault_>::create(*participant_, sim::kSimFaultTopic));
    fault_writer_.emplace(*dds::Writer<hub_msgs_msg_dds__SimFault_>::create(*participant_, *fault_topic_));

    HubProcessOptions options;
    options.hub = "tool_ecu";
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(fault_writer_->wait_for_readers(1, kPatience)) << hub_->output();

    // The planner: the order of the moment, every 100 ms (none while quiet).
    planner_ = std::thread([this] {
      while (running_) {
        {
          const std::lock_guard lock(mutex_);
          if (!action_.empty()) {
            hub_msgs::LiftCommand command;
            command.set_target_type("lift");
            command.set_target_name("lift");
            command.set_action(action_);
            command.set_position(position_);
            EXPECT_TRUE(command_writer_->write(command.wire()).is_ok());
          }
        }
        std::this_thread::sleep_for(milliseconds(100));
      }
    });
  }
  void TearDown() override {
    running_ = false;
    if (planner_.joinable()) planner_.join();
  }

  void order(std::string action, std::string position = "") {
    const std::lock_guard lock(mutex_);
    action_ = std::move(action);
    position_ = std::move(position);
  }

  // Takes States until `done` holds for one; false after kPatience.
  bool wait_for_state(const std::function<bool(const LiftState&)>& done) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (done(state_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(5));
    }
    return false;
  }
  bool wait_for_lifecycle(Lifecycle wanted) {
    return wait_for_state(
        [wanted](const LiftState& s) { return s.header.lifecycle == static_cast<std::uint8_t>(wanted); });
  }
  bool wait_for_diagnostics(const std::function<bool(const Diagnostics&)>& done) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = diagnostics_reader_->take_next(diagnostics_);
      if (taken.is_ok() && taken.value()) {
        if (done(diagnostics_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(5));
    }
    return false;
  }
  std::string describe() {
    const LiftState& s = state_.get();
    return fmt::format(
        "last lift State: lifecycle {} ({}), fresh_msg {}, target '{}', moving {}, errors '{}'\nhubd:\n{}",
        s.header.lifecycle, runtime::lifecycle_name(s.header.lifecycle), s.fresh_msg,
        static_cast<const char*>(s.target), s.moving, joined(s), hub_->output());
  }
  void sim_fault(const std::string& fault) {
    const std::string hub = "tool_ecu", device = "lift_drive";
    hub_msgs_msg_dds__SimFault_ message{wire(hub), wire(device), wire(fault), 0};
    ASSERT_TRUE(fault_writer_->write(message).is_ok());
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<LiftCommand>> command_topic_;
  std::optional<dds::Writer<LiftCommand>> command_writer_;
  std::optional<dds::Topic<LiftState>> state_topic_;
  std::optional<dds::Reader<LiftState>> state_reader_;
  std::optional<dds::Topic<Diagnostics>> diagnostics_topic_;
  std::optional<dds::Reader<Diagnostics>> diagnostics_reader_;
  std::optional<dds::Topic<hub_msgs_msg_dds__SimFault_>> fault_topic_;
  std::optional<dds::Writer<hub_msgs_msg_dds__SimFault_>> fault_writer_;
  std::optional<HubProcess> hub_;
  dds::Sample<LiftState> state_;
  dds::Sample<Diagnostics> diagnostics_;

  std::mutex mutex_;  // guards the order
  std::string action_;
  std::string position_;
  std::atomic<bool> running_{true};
  std::thread planner_;
};

TEST_F(HubdLifecycleTest, SafeOperationalSafeFaultAndBackOnTheWireAndInDiagnostics) {
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kSafe)) << "no command yet: safe\n" << describe();

  order("stop");
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kOperational)) << describe();
  EXPECT_TRUE(state_.get().fresh_msg);

  order("");  // the planner goes quiet: safe after the command timeout (1 s)
  ASSERT_TRUE(wait_for_state([](const LiftState& s) { return !s.fresh_msg; })) << describe();
  EXPECT_EQ(state_.get().header.lifecycle, static_cast<std::uint8_t>(Lifecycle::kSafe)) << describe();

  order("move", "work");
  ASSERT_TRUE(wait_for_state([](const LiftState& s) {
    return s.header.lifecycle == static_cast<std::uint8_t>(Lifecycle::kOperational) && s.moving;
  })) << describe();

  sim_fault("overcurrent");
  ASSERT_TRUE(wait_for_lifecycle(Lifecycle::kFault)) << describe();
  // The move stays in force, yet the lift is held in its safe state: stopped, no target.
  ASSERT_TRUE(wait_for_state([](const LiftState& s) { return s.fault && !s.moving; })) << describe();
  EXPECT_EQ(state_.get().header.lifecycle, static_cast<std::uint8_t>(Lifecycle::kFault)) << describe();
  EXPECT_TRUE(state_.get().fresh_msg);
  EXPECT_STREQ(state_.get().target, "");

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
      value_of(diagnostics_.get(), "tool_ecu: lift", "lifecycle_transitions").value_or("0");
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
