// Nothing outside the hub holds its cycle (issue 29, point 3). hubd runs the Dock ECU at 100 Hz,
// its log at debug level with a planner changing its command every 2 ms (a debug line each), and:
//   - stderr is a pipe whose reader stays open but never reads (a stalled journald): the pipe
//     fills within seconds, then the log queue; from then on lines are dropped and counted;
//   - stderr is /dev/full (a full disk): every line fails with ENOSPC, dropped and counted;
//   - a reliable State subscriber in another process is stopped (SIGSTOP) and never acknowledges.
// In each case the test's own State reader sees the heartbeat go on (at most a 1 s gap: generous,
// a loaded 2-core machine under sanitizers; a held cycle shows as a gap of the whole stall), a
// new command still takes effect, the planner's silence still makes the node safe on its
// timeout, and SIGTERM ends hubd promptly with status 0. Before issue 29, the stalled pipe
// stopped the heartbeat after 8 s and hubd did not exit on SIGTERM until the reader went away.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <functional>
#include <map>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/time_to_safe.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockCommand;
using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;
using Diagnostics = diagnostic_msgs_msg_dds__DiagnosticArray_;

constexpr auto kPatience = seconds(20);   // start-up under sanitizers on a loaded machine
constexpr auto kLongestGap = seconds(1);  // 100 periods: a held cycle shows as the whole stall
constexpr std::uint8_t kOperational = 3;

enum class Hazard { kStalledLogPipe, kFullDisk, kStoppedSubscriber };

std::string hazard_name(Hazard hazard) {
  switch (hazard) {
    case Hazard::kStalledLogPipe:
      return "StalledLogPipe";
    case Hazard::kFullDisk:
      return "FullDisk";
    case Hazard::kStoppedSubscriber:
      return "StoppedSubscriber";
  }
  return "?";
}

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

struct Seen {
  SteadyClock::time_point at;
  std::uint8_t lifecycle;
  bool fresh;
  std::string echo;
};

class HubdHeartbeatHoldsTest : public ::testing::TestWithParam<Hazard> {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    command_topic_.emplace(*dds::Topic<DockCommand>::create(*participant_, "/dock/command"));
    command_writer_.emplace(*dds::Writer<DockCommand>::create(*participant_, *command_topic_));
    state_topic_.emplace(*dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state"));
    state_reader_.emplace(
        *dds::Reader<DockState>::create(*participant_, *state_topic_, dds::Qos::ros2_default(100)));
    diagnostics_topic_.emplace(*dds::Topic<Diagnostics>::create(*participant_, "/diagnostics"));
    diagnostics_reader_.emplace(*dds::Reader<Diagnostics>::create(*participant_, *diagnostics_topic_));
    ASSERT_NO_FATAL_FAILURE(start_hub());
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience));
    if (GetParam() == Hazard::kStoppedSubscriber) {
      auto echo = test_support::ChildProcess::start(
          HUBRT_HUBCTL_PATH, {"echo", "/dock_ecu/dock/state", "--timeout", "20"}, domain_->env());
      ASSERT_TRUE(echo) << echo.error().message;
      subscriber_.emplace(std::move(*echo));
      ASSERT_TRUE(subscriber_->wait_for_output("header", kPatience)) << subscriber_->stderr_text();
      ASSERT_TRUE(subscriber_->signal(SIGSTOP));  // a reliable reader that never acknowledges again
    }
    worker_ = std::thread([this] { plan_and_watch(); });
  }

  void TearDown() override {
    running_ = false;
    if (worker_.joinable()) worker_.join();
    if (subscriber_) (void)subscriber_->signal(SIGCONT);
    if (reader_end_ >= 0) ::close(reader_end_);
  }

  // hubd with its stderr on the hazard's file: a pipe whose reading end this test keeps open and
  // never reads, /dev/full, or files (the stopped-subscriber case).
  void start_hub() {
    const std::string hubd = test_support::hubd_path();
    std::vector<std::string> args = {"-c",    "",         "sh",     hubd,  "--board",     "host-sim",
                                     "--hub", "dock_ecu", "--rate", "100", "--log-level", "debug"};
    switch (GetParam()) {
      case Hazard::kStalledLogPipe: {
        std::array<int, 2> fds{-1, -1};
        ASSERT_EQ(::pipe2(fds.data(), O_CLOEXEC), 0);
        reader_end_ = fds[0];
        // The writing end goes to the child without close-on-exec, and the shell makes it the
        // child's stderr (through /proc: dash's `2>&N` takes one digit only).
        writer_fd_ = ::fcntl(fds[1], F_DUPFD, 3);
        ::close(fds[1]);
        args[1] = fmt::format("exec \"$@\" 2>/proc/self/fd/{}", writer_fd_);
        break;
      }
      case Hazard::kFullDisk:
        args[1] = "exec \"$@\" 2>/dev/full";
        break;
      case Hazard::kStoppedSubscriber:
        args[1] = "exec \"$@\"";
        break;
    }
    test_support::Environment env = domain_->env();
    env.emplace_back("HUBRT_CONFIG_DIR", HUBRT_SOURCE_DIR);
    auto hub = test_support::ChildProcess::start("/bin/sh", args, env);
    if (writer_fd_ >= 0) ::close(writer_fd_);  // the child has its copy
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
  }

  // The planner changes its command every 2 ms while `busy_`, else repeats `steady_` every 50 ms
  // (or nothing when it is empty); every State is recorded.
  void plan_and_watch() {
    DockCommand command{};
    hubrt::msgs::typed::assign(command.target_type, "dock");
    hubrt::msgs::typed::assign(command.target_name, "dock");
    dds::Sample<DockState> sample;
    std::uint64_t n = 0;
    auto next = SteadyClock::now();
    while (running_) {
      if (SteadyClock::now() >= next) {
        std::string action;
        {
          const std::lock_guard lock(mutex_);
          action = busy_ ? (n++ % 2 == 0 ? "monitor" : "reset") : steady_;
        }
        if (!action.empty()) {
          hubrt::msgs::typed::assign(command.action, action);
          command_writer_->write(command).ignore();
        }
        next += busy_ ? milliseconds(2) : milliseconds(50);
      }
      while (state_reader_->take_next(sample).value_or(false)) {
        const std::lock_guard lock(mutex_);
        seen_.push_back(Seen{SteadyClock::now(), sample.get().header.lifecycle, sample.get().fresh_msg,
                             std::string(sample.get().echo.action)});
      }
      std::this_thread::sleep_for(milliseconds(1));
    }
  }
  void set_plan(bool busy, std::string steady) {
    const std::lock_guard lock(mutex_);
    busy_ = busy;
    steady_ = std::move(steady);
  }
  std::vector<Seen> seen_since(SteadyClock::time_point from) {
    const std::lock_guard lock(mutex_);
    std::vector<Seen> out;
    for (const Seen& s : seen_) {
      if (s.at >= from) out.push_back(s);
    }
    return out;
  }
  // The first State since `from` that satisfies `done`, waiting up to kPatience.
  std::optional<Seen> first_since(SteadyClock::time_point from,
                                  const std::function<bool(const Seen&)>& done) {
    const auto deadline = SteadyClock::now() + kPatience;
    while (SteadyClock::now() < deadline) {
      for (const Seen& s : seen_since(from)) {
        if (done(s)) return s;
      }
      std::this_thread::sleep_for(milliseconds(10));
    }
    return std::nullopt;
  }
  // The latest log_lines_dropped from /diagnostics once it is above zero, waiting up to kPatience.
  std::uint64_t dropped_lines() {
    dds::Sample<Diagnostics> diagnostics;
    std::uint64_t dropped = 0;
    const auto deadline = SteadyClock::now() + kPatience;
    while (SteadyClock::now() < deadline && dropped == 0) {
      while (diagnostics_reader_->take_next(diagnostics).value_or(false)) {
        dropped = std::stoull(cycle_value(diagnostics.get(), "log_lines_dropped").value_or("0"));
      }
      std::this_thread::sleep_for(milliseconds(50));
    }
    return dropped;
  }
  // Fails on a gap longer than kLongestGap between States from `from` to now.
  void expect_heartbeat_since(SteadyClock::time_point from, const char* what) {
    const auto states = seen_since(from);
    ASSERT_GT(states.size(), 10u) << what;
    Duration longest{0};
    for (std::size_t i = 1; i < states.size(); ++i)
      longest = std::max<Duration>(longest, states[i].at - states[i - 1].at);
    longest = std::max<Duration>(longest, SteadyClock::now() - states.back().at);
    EXPECT_LT(longest, kLongestGap) << what << ": the heartbeat stopped for " << to_seconds(longest) << " s";
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockCommand>> command_topic_;
  std::optional<dds::Writer<DockCommand>> command_writer_;
  std::optional<dds::Topic<DockState>> state_topic_;
  std::optional<dds::Reader<DockState>> state_reader_;
  std::optional<dds::Topic<Diagnostics>> diagnostics_topic_;
  std::optional<dds::Reader<Diagnostics>> diagnostics_reader_;
  std::optional<test_support::ChildProcess> hub_;
  std::optional<test_support::ChildProcess> subscriber_;
  int reader_end_ = -1;
  int writer_fd_ = -1;
  std::atomic<bool> running_{true};
  std::thread worker_;
  std::mutex mutex_;
  bool busy_ = true;
  std::string steady_;
  std::vector<Seen> seen_;
};

TEST_P(HubdHeartbeatHoldsTest, TheHeartbeatCommandsTimeoutAndSigtermHold) {
  const auto start = SteadyClock::now();
  // Logging hard (a debug line per command) until the log path is stuck, and 10 s beyond.
  if (GetParam() != Hazard::kStoppedSubscriber) {
    EXPECT_GT(dropped_lines(), 0u) << "the log path never filled: the test would prove nothing";
  }
  std::this_thread::sleep_for(seconds(10));
  expect_heartbeat_since(start + seconds(2), "while the planner floods the log");

  // A new command still takes effect...
  set_plan(false, "monitor");
  const auto commanded = SteadyClock::now();
  const auto acted = first_since(
      commanded, [](const Seen& s) { return s.echo == "monitor" && s.fresh && s.lifecycle == kOperational; });
  ASSERT_TRUE(acted) << "a command did not take effect";
  std::this_thread::sleep_for(seconds(1));
  // ... and the planner's silence still makes the node safe on its timeout (1 s).
  set_plan(false, "");
  const auto silent = SteadyClock::now();
  const auto safe =
      first_since(silent, [](const Seen& s) { return !s.fresh && s.lifecycle != kOperational; });
  ASSERT_TRUE(safe) << "the node never went safe";
  const double to_safe = to_seconds(safe->at - silent);
  EXPECT_LT(to_safe, 1.0 + 0.5) << "command timeout + slack: " << to_safe << " s";
  std::this_thread::sleep_for(seconds(1));
  expect_heartbeat_since(start + seconds(2), "over the whole run");

  const std::map<Hazard, std::pair<std::string, std::string>> rows{
      {Hazard::kStalledLogPipe, {"log stall (stderr a pipe nobody reads), planner stops", "log_stall_dock"}},
      {Hazard::kFullDisk, {"full disk (stderr /dev/full), planner stops", "full_disk_dock"}},
      {Hazard::kStoppedSubscriber,
       {"a State subscriber stopped (SIGSTOP, never acknowledges), planner stops",
        "stopped_subscriber_dock"}}};
  test_support::record_time_to_safe(
      rows.at(GetParam()).second,
      test_support::TimeToSafe{rows.at(GetParam()).first, "dock_ecu",
                               "none (dock sensors only): lifecycle safe",
                               "command watchdog in the cycle; the log goes through a bounded queue "
                               "(lines dropped and counted), keep-last writers never block on a reader",
                               to_safe, 1.0 + 0.01 + 0.1, "command timeout + one period (+0.1 s reader)",
                               "hubrt_hubd_heartbeat_holds_test"});

  // SIGTERM is honoured whatever stderr does: outputs safe, exit 0, promptly.
  ASSERT_TRUE(hub_->signal(SIGTERM));
  const auto terminated = SteadyClock::now();
  auto status = hub_->wait(seconds(10));
  ASSERT_TRUE(status) << "hubd did not exit on SIGTERM";
  EXPECT_TRUE(status->exited_with(0)) << status->describe();
  EXPECT_LT(to_seconds(SteadyClock::now() - terminated), 3.0) << "the stop waits 0.5 s for the log at most";
}

INSTANTIATE_TEST_SUITE_P(Hazards, HubdHeartbeatHoldsTest,
                         ::testing::Values(Hazard::kStalledLogPipe, Hazard::kFullDisk,
                                           Hazard::kStoppedSubscriber),
                         [](const ::testing::TestParamInfo<Hazard>& param) {
                           return hazard_name(param.param);
                         });

}  // namespace
}  // namespace hubrt::integration
