// A hub whose stdout and stderr lead nowhere — `hubd ... | head -1` after head exited, a terminal
// or SSH session gone — keeps running: SIGPIPE is ignored, each log line that cannot be written is
// dropped and counted (log_lines_dropped in /diagnostics), and the heartbeat goes on. Old hubd
// died of SIGPIPE on its first log line.
#include <csignal>
#include <functional>
#include <string>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/base/exit_codes.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "dock_messages.h"
#include "hub_process.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using std::chrono::milliseconds;
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

template <class T>
bool take_until(dds::Reader<T>& reader, dds::Sample<T>& sample, const std::function<bool(const T&)>& done) {
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < deadline) {
    const Result<bool> taken = reader.take_next(sample);
    if (taken.is_ok() && taken.value()) {
      if (done(sample.get())) return true;
      continue;
    }
    std::this_thread::sleep_for(milliseconds(5));
  }
  return false;
}

TEST(HubdClosedOutput, KeepsRunningAndCountsTheLostLogLines) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "test");
  ASSERT_TRUE(participant) << participant.error().message;
  auto state_topic = dds::Topic<DockState>::create(*participant, "/dock_ecu/dock/state");
  ASSERT_TRUE(state_topic);
  auto states = dds::Reader<DockState>::create(*participant, *state_topic);
  ASSERT_TRUE(states);
  auto diagnostics_topic = dds::Topic<Diagnostics>::create(*participant, "/diagnostics");
  ASSERT_TRUE(diagnostics_topic);
  auto diagnostics = dds::Reader<Diagnostics>::create(*participant, *diagnostics_topic);
  ASSERT_TRUE(diagnostics);
  auto input_topic = dds::Topic<hub_msgs_msg_dds__SimInput_>::create(*participant, sim::kSimInputTopic);
  ASSERT_TRUE(input_topic);
  auto input = dds::Writer<hub_msgs_msg_dds__SimInput_>::create(*participant, *input_topic);
  ASSERT_TRUE(input);

  test_support::Environment env = domain->env();
  env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
  auto hub = test_support::ChildProcess::start(HUBRT_HUBD_PATH, {"--board", "host-sim", "--hub", "dock_ecu"},
                                               env, test_support::OutputMode::kClosedPipe);
  ASSERT_TRUE(hub) << hub.error().message;

  // Started and logged "running hub ..." into the dead pipe: the heartbeat arrives anyway.
  dds::Sample<DockState> state;
  ASSERT_TRUE(take_until<DockState>(*states, state, [](const DockState&) { return true; }))
      << "no State: " << [&] {
           auto status = hub->wait(milliseconds(1));
           return status ? status->describe() : std::string("hubd still runs");
         }();

  // A warning mid-run (an input this board does not simulate) goes to the dead pipe too.
  ASSERT_TRUE(input->wait_for_readers(1, kPatience));
  hub_msgs_msg_dds__SimInput_ unknown{};
  unknown.hub = const_cast<char*>("dock_ecu");       // NOLINT: the wire type wants char*
  unknown.signal = const_cast<char*>("no.such.in");  // NOLINT
  unknown.active = true;
  ASSERT_TRUE(input->write(unknown).is_ok());

  // Counted: at least "running hub ..." and the warning.
  dds::Sample<Diagnostics> array;
  std::string dropped;
  EXPECT_TRUE(take_until<Diagnostics>(*diagnostics, array,
                                      [&](const Diagnostics& a) {
                                        dropped = cycle_value(a, "log_lines_dropped").value_or("");
                                        return !dropped.empty() && std::stoull(dropped) >= 2;
                                      }))
      << "log_lines_dropped: '" << dropped << "'";

  // And the heartbeat goes on after it: ten more States (a second at 10 Hz).
  int more = 0;
  EXPECT_TRUE(take_until<DockState>(*states, state, [&](const DockState&) { return ++more == 10; }));

  ASSERT_TRUE(hub->signal(SIGTERM));
  auto status = hub->wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::kOk)) << status->describe();
}

}  // namespace
}  // namespace hubrt::integration
