// A hub whose stdout and stderr lead nowhere — `hubd ... | head -1` after head exited, a terminal
// or SSH session gone — keeps running: SIGPIPE is ignored, each log line that cannot be written is
// dropped and counted (log_lines_dropped in /diagnostics), and the heartbeat goes on. Old hubd
// died of SIGPIPE on its first log line.
#include <csignal>
#include <functional>
#include <string>

#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/base/exit_codes.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
using test_support::StateStream;
using Diagnostics = diagnostic_msgs_msg_dds__DiagnosticArray_;

// Generous: a busy 2-core machine running sanitizer builds in parallel; diagnostics come at 1 Hz.
constexpr auto kPatience = std::chrono::seconds(20);

// The value of `key` in the hub's cycle status ("dock_ecu: cycle"), if present.
std::optional<std::string> cycle_value(const Diagnostics& array, std::string_view key) {
  for (std::uint32_t i = 0; i < array.status._length; ++i) {
    const auto& status = array.status._buffer[i];
    if (status.name == nullptr || std::string_view(status.name) != "dock_ecu: cycle") continue;
    for (std::uint32_t k = 0; k < status.values._length; ++k) {
      const auto& pair = status.values._buffer[k];
      if (pair.key != nullptr && key == pair.key) return std::string(pair.value);
    }
  }
  return std::nullopt;
}

TEST(HubdClosedOutput, KeepsRunningAndCountsTheLostLogLines) {
  StateStream<DockState>* states = nullptr;
  StateStream<Diagnostics>* diagnostics = nullptr;
  test_support::HubUnderTest hub(kPatience);
  ASSERT_NO_FATAL_FAILURE(hub.open("test"));
  ASSERT_NO_FATAL_FAILURE(hub.make_stream(states, "/dock_ecu/dock/state"));
  ASSERT_NO_FATAL_FAILURE(hub.make_stream(diagnostics, "/diagnostics"));
  ASSERT_NO_FATAL_FAILURE(hub.start_unmatched({.output = test_support::OutputMode::kClosedPipe}));

  // Started and logged "running hub ..." into the dead pipe: the heartbeat arrives anyway.
  ASSERT_TRUE(states->take_any(kPatience)) << "no State: " << [&] {
    auto status = hub.hub().process().wait(milliseconds(1));
    return status ? status->describe() : std::string("hubd still runs");
  }();

  // A warning mid-run (an input this board does not simulate) goes to the dead pipe too.
  ASSERT_NO_FATAL_FAILURE(hub.sim_input("dock_ecu", "no.such.in", true));

  // Counted: at least "running hub ..." and the warning.
  std::string dropped;
  EXPECT_TRUE(diagnostics->take_until(
      [&](const Diagnostics& a) {
        dropped = cycle_value(a, "log_lines_dropped").value_or("");
        return !dropped.empty() && std::stoull(dropped) >= 2;
      },
      kPatience))
      << "log_lines_dropped: '" << dropped << "'";

  // And the heartbeat goes on after it: ten more States (a second at 10 Hz).
  int more = 0;
  EXPECT_TRUE(states->take_until([&](const DockState&) { return ++more == 10; }, kPatience));

  ASSERT_TRUE(hub.hub().process().signal(SIGTERM));
  auto status = hub.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::kOk)) << status->describe();
}

}  // namespace
}  // namespace hubrt::integration
