// hubd as a process, on the fake HAL, talked to over real Cyclone DDS on loopback in a private
// domain: the Dock ECU slice end to end.
#include <unistd.h>

#include <csignal>
#include <functional>
#include <thread>

#include <gtest/gtest.h>
#include <sys/socket.h>
#include <sys/un.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "dock_messages.h"
#include "hub_process.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockCommand;
using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;

// Generous: a busy 2-core CI machine running sanitizer builds in parallel. These tests check
// behaviour, not timing; the benchmarks measure timing.
constexpr auto kPatience = seconds(15);

std::string error_list(const DockState& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

class HubdDockTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    auto command_topic = dds::Topic<DockCommand>::create(*participant_, "/dock/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto writer = dds::Writer<DockCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(writer) << writer.error().message;
    command_writer_.emplace(std::move(*writer));
    auto state_topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<DockState>::create(*participant_, *state_topic_);
    ASSERT_TRUE(reader) << reader.error().message;
    state_reader_.emplace(std::move(*reader));
  }

  void start_hub(std::vector<std::string> extra_args = {}) {
    HubProcessOptions options;
    options.extra_args = std::move(extra_args);
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(state_reader_->wait_for_writers(1, kPatience)) << hub_->output();
  }

  // Takes States until one satisfies `predicate`; false after `timeout`.
  bool wait_for_state(const std::function<bool(const DockState&)>& predicate, Duration timeout = kPatience) {
    const auto deadline = std::chrono::steady_clock::now() + timeout;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = state_reader_->take_next(state_);
      if (taken.is_ok() && taken.value()) {
        if (predicate(state_.get())) return true;
        continue;
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
    return false;
  }

  void send(const char* action, const char* target_name = "dock", const char* target_type = "dock") {
    DockCommand command{};
    hubrt::msgs::typed::assign(command.target_type, target_type);
    hubrt::msgs::typed::assign(command.target_name, target_name);
    hubrt::msgs::typed::assign(command.action, action);
    ASSERT_TRUE(command_writer_->write(command).is_ok());
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockCommand>> command_topic_;
  std::optional<dds::Writer<DockCommand>> command_writer_;
  std::optional<dds::Topic<DockState>> state_topic_;
  std::optional<dds::Reader<DockState>> state_reader_;
  dds::Sample<DockState> state_;
  std::optional<HubProcess> hub_;
};

TEST_F(HubdDockTest, PublishesItsStateAtTheConfiguredRateWithIncreasingSequence) {
  start_hub({"--rate", "20"});
  ASSERT_TRUE(wait_for_state([](const DockState&) { return true; })) << hub_->output();
  std::uint64_t first_seq = state_.get().header.seq;
  std::uint64_t last_seq = first_seq;
  int samples = 1;
  const auto start = std::chrono::steady_clock::now();
  while (std::chrono::steady_clock::now() - start < seconds(2)) {
    const Result<bool> taken = state_reader_->take_next(state_);
    if (!taken.is_ok() || !taken.value()) {
      std::this_thread::sleep_for(milliseconds(2));
      continue;
    }
    EXPECT_GT(state_.get().header.seq, last_seq) << "sequence numbers only go up";
    last_seq = state_.get().header.seq;
    ++samples;
  }
  // 2 s at 20 Hz is 40 States. Bounds are wide (a loaded machine may stall a process for a
  // while); they still catch a hub that publishes at 10 Hz or only on change.
  EXPECT_GE(samples, 25) << hub_->output();
  EXPECT_LE(samples, 60);
  EXPECT_LE(last_seq - first_seq + 1 - static_cast<std::uint64_t>(samples), 2u) << "States lost on loopback";
  EXPECT_STREQ(state_.get().name, "dock");
  ASSERT_EQ(state_.get().slots._length, 4u);
}

TEST_F(HubdDockTest, EchoesACommandAndDropsFreshMsgWhenCommandsStop) {
  start_hub();
  ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience));
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return !s.fresh_msg; }))
      << "not fresh before any command";
  // Like the planner: the same command, repeatedly.
  std::atomic<bool> sending{true};
  std::thread planner([&] {
    while (sending) {
      send("monitor");
      std::this_thread::sleep_for(milliseconds(50));
    }
  });
  const bool echoed = wait_for_state([](const DockState& s) {
    return s.fresh_msg && std::string(s.echo.action) == "monitor" &&
           std::string(s.echo.target_name) == "dock";
  });
  sending = false;
  planner.join();
  ASSERT_TRUE(echoed) << hub_->output();
  EXPECT_STREQ(state_.get().echo.target_type, "dock");
  EXPECT_EQ(state_.get().error_list._length, 0u) << error_list(state_.get());
  // The planner went quiet: after the 1 s command timeout fresh_msg turns false with an error.
  ASSERT_TRUE(wait_for_state([](const DockState& s) { return !s.fresh_msg; })) << hub_->output();
  EXPECT_NE(error_list(state_.get()).find("command timeout"), std::string::npos) << error_list(state_.get());
  EXPECT_STREQ(state_.get().echo.action, "monitor") << "the echo still shows the last command";
}

TEST_F(HubdDockTest, RejectsABadCommandWithItsReason) {
  start_hub();
  ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience));
  send("dance");
  ASSERT_TRUE(wait_for_state([](const DockState& s) {
    return error_list(s).find("rejected command: unknown action 'dance' (expected one of: monitor, reset)") !=
           std::string::npos;
  })) << hub_->output();
  EXPECT_FALSE(state_.get().fresh_msg);
  EXPECT_TRUE(hub_->process().wait_for_output("rejected command", kPatience)) << "and it is logged";
}

TEST_F(HubdDockTest, AStateChangesWhenASimulatedSensorChanges) {
  start_hub();
  ASSERT_TRUE(wait_for_state(
      [](const DockState& s) { return s.slots._length == 4 && !s.slots._buffer[2].occupied; }));
  auto topic = dds::Topic<hub_msgs_msg_dds__SimInput_>::create(*participant_, sim::kSimInputTopic);
  ASSERT_TRUE(topic);
  auto writer = dds::Writer<hub_msgs_msg_dds__SimInput_>::create(*participant_, *topic);
  ASSERT_TRUE(writer);
  ASSERT_TRUE(writer->wait_for_readers(1, kPatience));
  hub_msgs_msg_dds__SimInput_ input{};
  input.hub = const_cast<char*>("dock_ecu");                 // NOLINT
  input.signal = const_cast<char*>("dock.slot.smart_tool");  // NOLINT
  input.active = true;
  ASSERT_TRUE(writer->write(input).is_ok());
  ASSERT_TRUE(wait_for_state([](const DockState& s) {
    return s.slots._length == 4 && s.slots._buffer[2].occupied;
  })) << hub_->output();
  EXPECT_STREQ(state_.get().slots._buffer[2].name, "smart_tool");
}

TEST_F(HubdDockTest, StopsCleanlyOnSigtermWithOutputsSafe) {
  start_hub();
  ASSERT_TRUE(hub_->process().signal(SIGTERM));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(0)) << status->describe() << "\n" << hub_->output();
  EXPECT_NE(hub_->output().find("outputs driven to their safe state"), std::string::npos) << hub_->output();
}

TEST_F(HubdDockTest, TellsSystemdItIsReadyAndPingsTheWatchdog) {
  // A datagram socket standing in for systemd's notify socket.
  const std::string path = fmt::format("/tmp/hubrt-notify-{}-{}.sock", getpid(), domain_->domain_id());
  const int fd = socket(AF_UNIX, SOCK_DGRAM | SOCK_CLOEXEC, 0);
  ASSERT_GE(fd, 0);
  sockaddr_un address{};
  address.sun_family = AF_UNIX;
  path.copy(address.sun_path, sizeof(address.sun_path) - 1);
  unlink(path.c_str());
  ASSERT_EQ(bind(fd, reinterpret_cast<const sockaddr*>(&address), sizeof address), 0);  // NOLINT
  HubProcessOptions options;
  options.extra_env = {{"NOTIFY_SOCKET", path}, {"WATCHDOG_USEC", "400000"}};
  auto hub = HubProcess::start(*domain_, options);
  ASSERT_TRUE(hub) << hub.error().message;
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
