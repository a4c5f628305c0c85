// hubd --trace-stages (runtime/stage_trace.h, issue 33): a command's way through the hub, stamped
// stage by stage — Cyclone's listener, the cycle thread's wake, the step, the write — and written
// as CSV at exit. The benchmarks read it to tell a slow round trip that was the hub's from one that
// was the host's; stamps out of order, missing or from another clock would mislead them.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockCommand;
using dock_ecu::DockState;
using test_support::HubUnderTest;
using test_support::StateStream;

struct Row {
  std::int64_t listener = 0, woke = 0, stepped = 0, written = 0;
};

DockCommand dock_command(const char* action) {
  DockCommand command{};
  msgs::typed::assign(command.target_type, "dock");
  msgs::typed::assign(command.target_name, "dock");
  msgs::typed::assign(command.action, action);
  return command;
}

TEST(HubdTraceStages, EveryCommandThatTookEffectHasItsStagesInOrderWithinTheRoundTrip) {
  const std::string csv =
      (std::filesystem::temp_directory_path() / fmt::format("hubrt-trace-stages-{}.csv", getpid())).string();
  std::filesystem::remove(csv);
  HubUnderTest hub;
  dds::Writer<DockCommand>* commands = nullptr;
  StateStream<DockState>* states = nullptr;
  ASSERT_NO_FATAL_FAILURE(hub.open());
  ASSERT_NO_FATAL_FAILURE(hub.make_writer(commands, "/dock/command"));
  ASSERT_NO_FATAL_FAILURE(hub.make_stream(states, "/dock_ecu/dock/state"));
  ASSERT_NO_FATAL_FAILURE(hub.start({.extra_args = {"--trace-stages", csv}}));
  ASSERT_TRUE(hub.wait_for(
      *states, [](const DockState&) { return true; }, "a first State"));
  // Alternating actions, each written once after the echo of the one before: each takes effect.
  constexpr int kCommands = 6;
  for (int i = 0; i < kCommands; ++i) {
    const char* action = i % 2 == 0 ? "reset" : "monitor";
    ASSERT_TRUE(commands->write(dock_command(action)).is_ok());
    ASSERT_TRUE(hub.wait_for(
        *states, [action](const DockState& s) { return s.fresh_msg && std::string(s.echo.action) == action; },
        fmt::format("the echo of command {} ({})", i, action)));
  }
  ASSERT_TRUE(hub.stops_cleanly(SIGTERM));

  std::ifstream in(csv);
  ASSERT_TRUE(in) << csv << " was not written; hubd said:\n" << hub.output();
  std::string comment, header, line;
  std::getline(in, comment);
  std::getline(in, header);
  EXPECT_EQ(comment.rfind("# hubd stage trace: ", 0), 0U) << comment;
  EXPECT_EQ(header, "listener_ns,woke_ns,stepped_ns,written_ns");
  std::vector<Row> complete;
  while (std::getline(in, line)) {
    Row r;
    char comma = 0;
    std::istringstream fields(line);
    fields >> r.listener >> comma >> r.woke >> comma >> r.stepped >> comma >> r.written;
    ASSERT_FALSE(fields.fail()) << "not four numbers: " << line;
    if (r.stepped != 0) complete.push_back(r);
  }
  // A command the periodic cycle happened to take first is no command step's: most are.
  EXPECT_GE(complete.size(), static_cast<std::size_t>(kCommands - 2)) << "command steps with an effect";
  for (const Row& r : complete) {
    EXPECT_GT(r.listener, 0) << "no listener stamp";
    EXPECT_LE(r.listener, r.woke);
    EXPECT_LE(r.woke, r.stepped);
    EXPECT_LE(r.stepped, r.written);
    // One clock for all four: the whole way through the hub takes far less than a second, even
    // under sanitizers on a loaded machine.
    EXPECT_LT(r.written - r.listener, 1'000'000'000) << "stamps from different clocks?";
  }
  std::filesystem::remove(csv);
}

}  // namespace
}  // namespace hubrt::integration
