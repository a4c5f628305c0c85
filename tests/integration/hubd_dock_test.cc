// hubd as a process, on the fake HAL, talked to over real Cyclone DDS on loopback in a private
// domain: the Dock ECU slice end to end.
#include <unistd.h>

#include <csignal>
#include <functional>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>

#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockCommand;
using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using test_support::HubProcessOptions;
using test_support::HubUnderTest;
using test_support::kPatience;
using test_support::StateStream;

std::string error_list(const DockState& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

DockCommand dock_command(const char* action, const char* target_name = "dock",
                         const char* target_type = "dock") {
  DockCommand command{};
  hubrt::msgs::typed::assign(command.target_type, target_type);
  hubrt::msgs::typed::assign(command.target_name, target_name);
  hubrt::msgs::typed::assign(command.action, action);
  return command;
}

class HubdDockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/dock/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(states_, "/dock_ecu/dock/state"));
  }

  void start_hub(std::vector<std::string> extra_args = {}) {
    hub_.start({.extra_args = std::move(extra_args)});
  }

  ::testing::AssertionResult wait_for(const std::function<bool(const DockState&)>& predicate,
                                      std::string_view what) {
    return hub_.wait_for(*states_, predicate, what);
  }
  const DockState& state() const { return states_->latest(); }

  dds::Writer<DockCommand>* commands_ = nullptr;
  StateStream<DockState>* states_ = nullptr;
  HubUnderTest hub_;
};

TEST_F(HubdDockTest, PublishesItsStateAtTheConfiguredRateWithIncreasingSequence) {
  ASSERT_NO_FATAL_FAILURE(start_hub({"--rate", "20"}));
  ASSERT_TRUE(wait_for([](const DockState&) { return true; }, "any State"));
  std::uint64_t first_seq = state().header.seq;
  std::uint64_t last_seq = first_seq;
  int samples = 1;
  const auto start = std::chrono::steady_clock::now();
  for (auto now = start; now - start < seconds(2); now = std::chrono::steady_clock::now()) {
    if (!states_->take_any(start + seconds(2) - now)) break;
    EXPECT_GT(state().header.seq, last_seq) << "sequence numbers only go up";
    last_seq = state().header.seq;
    ++samples;
  }
  // 2 s at 20 Hz is 40 States. Bounds are wide (a loaded machine may stall a process for a
  // while); they still catch a hub that publishes at 10 Hz or only on change.
  EXPECT_GE(samples, 25) << hub_.output();
  EXPECT_LE(samples, 60);
  EXPECT_LE(last_seq - first_seq + 1 - static_cast<std::uint64_t>(samples), 2u) << "States lost on loopback";
  EXPECT_STREQ(state().name, "dock");
  ASSERT_EQ(state().slots._length, 4u);
}

TEST_F(HubdDockTest, EchoesACommandAndDropsFreshMsgWhenCommandsStop) {
  ASSERT_NO_FATAL_FAILURE(start_hub());
  ASSERT_TRUE(wait_for([](const DockState& s) { return !s.fresh_msg; }, "not fresh before any command"));
  // Like the planner: the same command, repeatedly.
  hub_.plan(*commands_, dock_command("monitor"));
  const bool echoed = wait_for(
      [](const DockState& s) {
        return s.fresh_msg && std::string(s.echo.action) == "monitor" &&
               std::string(s.echo.target_name) == "dock";
      },
      "fresh, echoing 'monitor' to 'dock'");
  hub_.stop_planner();
  ASSERT_TRUE(echoed) << hub_.output();
  EXPECT_STREQ(state().echo.target_type, "dock");
  EXPECT_EQ(state().error_list._length, 0u) << error_list(state());
  // The planner went quiet: after the 1 s command timeout fresh_msg turns false with an error.
  ASSERT_TRUE(
      wait_for([](const DockState& s) { return !s.fresh_msg; }, "not fresh after the planner stopped"));
  EXPECT_NE(error_list(state()).find("command timeout"), std::string::npos) << error_list(state());
  EXPECT_STREQ(state().echo.action, "monitor") << "the echo still shows the last command";
}

TEST_F(HubdDockTest, RejectsABadCommandWithItsReason) {
  ASSERT_NO_FATAL_FAILURE(start_hub());
  ASSERT_TRUE(commands_->write(dock_command("dance")).is_ok());
  ASSERT_TRUE(wait_for(
      [](const DockState& s) {
        return error_list(s).find(
                   "rejected command: unknown action 'dance' (expected one of: monitor, reset)") !=
               std::string::npos;
      },
      "the rejection of 'dance' in error_list"));
  EXPECT_FALSE(state().fresh_msg);
  EXPECT_TRUE(hub_.hub().process().wait_for_output("rejected command", kPatience)) << "and it is logged";
}

TEST_F(HubdDockTest, AStateChangesWhenASimulatedSensorChanges) {
  ASSERT_NO_FATAL_FAILURE(start_hub());
  ASSERT_TRUE(
      wait_for([](const DockState& s) { return s.slots._length == 4 && !s.slots._buffer[2].occupied; },
               "4 slots, the third empty"));
  ASSERT_NO_FATAL_FAILURE(hub_.sim_input("dock_ecu", "dock.slot.smart_tool", true));
  ASSERT_TRUE(wait_for([](const DockState& s) { return s.slots._length == 4 && s.slots._buffer[2].occupied; },
                       "the third slot occupied"));
  EXPECT_STREQ(state().slots._buffer[2].name, "smart_tool");
}

TEST_F(HubdDockTest, StopsCleanlyOnSigtermWithOutputsSafe) {
  ASSERT_NO_FATAL_FAILURE(start_hub());
  EXPECT_TRUE(hub_.stops_cleanly(SIGTERM));
}

TEST_F(HubdDockTest, TellsSystemdItIsReadyAndPingsTheWatchdog) {
  // A datagram socket standing in for systemd's notify socket.
  const std::string path = fmt::format("/tmp/hubrt-notify-{}-{}.sock", getpid(), hub_.domain().domain_id());
  const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  unlink(path.c_str());
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);  // NOLINT
  HubProcessOptions options;
  options.extra_env = {{"NOTIFY_SOCKET", path}, {"WATCHDOG_USEC", "400000"}};
  ASSERT_NO_FATAL_FAILURE(hub_.start_unmatched(options));
  auto* hub = &hub_.hub();
  std::string received;
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < deadline && (received.find("READY=1") == std::string::npos ||
                                                         received.find("WATCHDOG=1") == std::string::npos)) {
    char buffer[4096];
    const ssize_t n = recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n > 0) {
      received.append(buffer, static_cast<std::size_t>(n));
      received += '\n';
    } else {
      std::this_thread::sleep_for(milliseconds(5));
    }
  }
  ASSERT_TRUE(hub->process().signal(SIGTERM));
  ASSERT_TRUE(hub->process().wait(kPatience));
  while (true) {  // drain what came with the stop
    char buffer[4096];
    const ssize_t n = recv(fd, buffer, sizeof buffer, MSG_DONTWAIT);
    if (n <= 0) break;
    received.append(buffer, static_cast<std::size_t>(n));
  }
  close(fd);
  unlink(path.c_str());
  // Start-up gets its own watchdog time, and READY puts the unit's back (systemd_notifier.h).
  const auto startup = received.find("WATCHDOG_USEC=30000000\nWATCHDOG=1");
  const auto ready = received.find("READY=1\nWATCHDOG_USEC=400000\nWATCHDOG=1\nSTATUS=hub 'dock_ecu'");
  ASSERT_NE(startup, std::string::npos) << received;
  ASSERT_NE(ready, std::string::npos) << received;
  EXPECT_LT(startup, ready) << received;
  EXPECT_NE(received.find("WATCHDOG=1"), std::string::npos) << received;
  EXPECT_NE(received.find("STOPPING=1"), std::string::npos) << received;
}

}  // namespace
}  // namespace hubrt::integration
