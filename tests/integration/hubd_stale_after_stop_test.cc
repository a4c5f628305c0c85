// Issue 29's first case with real processes: hubd runs the RSP ECU, `hubctl send` (a planner in a
// process of its own) holds the tool changer open (unlock) at 10 Hz; hubd is stopped (SIGSTOP),
// the planner is killed 0.3 s later, and hubd is continued 4 s after the stop. The samples that
// queued in hubd's socket while it was stopped are 3.7 to 4 s old when it reads them: none may
// act. After the continue no State may be operational or fresh, and the lock valve, closed by the
// watchdog, must never open again (the State's `lock` never goes back to opening/open). With the
// shipped hub file (clocks synced: the commands' ages) and with `clock_tolerance_ms: none` (the
// stall rule alone).
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <functional>
#include <mutex>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/time_to_safe.h"

#include "dock_messages.h"
#include "rsp_messages.h"

namespace hubrt::integration {
namespace {

using test_support::HubProcess;
using test_support::HubProcessOptions;

using dock_ecu::DockState;
using rsp_ecu::RspState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;
namespace fs = std::filesystem;

// Generous: start-up under sanitizers on a loaded 2-core machine. The test checks behaviour.
constexpr auto kPatience = seconds(20);
constexpr std::uint8_t kOperational = 3;
constexpr std::uint8_t kSafe = 2;

std::int64_t wall_ns() {
  return std::chrono::duration_cast<std::chrono::nanoseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

struct SeenState {
  SteadyClock::time_point received;
  std::int64_t stamp_ns = 0;  // the hub's wall clock when it published
  std::uint8_t lifecycle = 0;
  bool fresh_msg = false;
  std::string lock;
  std::string echo_action;
  [[nodiscard]] std::string describe() const {
    return fmt::format("lifecycle={} fresh={} lock={} echo={}", lifecycle, fresh_msg, lock, echo_action);
  }
};

std::string text(const char* s) {
  return s == nullptr ? std::string() : std::string(s);
}

class HubdStaleAfterStopTest : public ::testing::TestWithParam<bool> {  // param: clocks synced
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-dock-and-observer");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    auto dock_topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
    ASSERT_TRUE(dock_topic) << dock_topic.error().message;
    dock_topic_.emplace(std::move(*dock_topic));
    auto dock_writer = dds::Writer<DockState>::create(*participant_, *dock_topic_);
    ASSERT_TRUE(dock_writer) << dock_writer.error().message;
    dock_writer_.emplace(std::move(*dock_writer));
    auto state_topic = dds::Topic<RspState>::create(*participant_, "/rsp_ecu/rsp/state");
    ASSERT_TRUE(state_topic) << state_topic.error().message;
    state_topic_.emplace(std::move(*state_topic));
    auto reader = dds::Reader<RspState>::create(*participant_, *state_topic_, dds::Qos::ros2_default(100));
    ASSERT_TRUE(reader) << reader.error().message;
    state_reader_.emplace(std::move(*reader));

    HubProcessOptions options;
    options.hub = "rsp_ecu";
    if (!GetParam()) {
      std::ifstream in(std::string(HUBRT_SOURCE_DIR) + "/hubs/rsp_ecu/rsp_ecu.yaml");
      std::string yaml((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
      hub_file_ = fs::temp_directory_path() / fmt::format("hubrt-rsp-unsynced-{}.yaml", getpid());
      std::ofstream(hub_file_) << yaml << "clock_tolerance_ms: none\n";
      options.hub = hub_file_.string();
    }
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(dock_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    worker_ = std::thread([this] { dock_and_observe(); });
  }

  void TearDown() override {
    running_ = false;
    if (worker_.joinable()) worker_.join();
    if (hub_) (void)hub_->process().signal(SIGCONT);  // never leave a stopped child behind
    if (!hub_file_.empty()) fs::remove(hub_file_);
  }

  // The Dock ECU (the smart tool home, so that the interlock allows the unlock) every 50 ms, and
  // every RSP State as it arrives.
  void dock_and_observe() {
    std::array<hub_msgs_msg_dds__DockSlot_, 3> slots{
        {{"ladder_frame_tool", true}, {"filter_tool", true}, {"smart_tool", true}}};
    DockState dock{};
    hubrt::msgs::typed::assign(dock.name, "dock");
    hubrt::msgs::typed::assign(dock.echo.target_type, "");
    hubrt::msgs::typed::assign(dock.echo.target_name, "");
    hubrt::msgs::typed::assign(dock.echo.action, "");
    dock.slots._buffer = slots.data();
    dock.slots._length = static_cast<std::uint32_t>(slots.size());
    dock.slots._maximum = dock.slots._length;
    auto next_dock = SteadyClock::now();
    dds::Sample<RspState> sample;
    while (running_) {
      if (SteadyClock::now() >= next_dock) {
        dock_writer_->write(dock).ignore();
        next_dock += milliseconds(50);
      }
      while (state_reader_->take_next(sample).value_or(false)) {
        const RspState& s = sample.get();
        SeenState seen{SteadyClock::now(),
                       static_cast<std::int64_t>(s.header.stamp.sec) * 1'000'000'000 + s.header.stamp.nanosec,
                       s.header.lifecycle,
                       s.fresh_msg,
                       text(s.lock),
                       text(s.echo.action)};
        const std::lock_guard lock(mutex_);
        states_.push_back(std::move(seen));
      }
      std::this_thread::sleep_for(milliseconds(2));
    }
  }

  std::vector<SeenState> states() {
    const std::lock_guard lock(mutex_);
    return states_;
  }
  bool wait_for_state(const std::function<bool(const SeenState&)>& predicate) {
    const auto deadline = SteadyClock::now() + kPatience;
    while (SteadyClock::now() < deadline) {
      for (const SeenState& s : states()) {
        if (predicate(s)) return true;
      }
      std::this_thread::sleep_for(milliseconds(20));
    }
    return false;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> dock_topic_;
  std::optional<dds::Writer<DockState>> dock_writer_;
  std::optional<dds::Topic<RspState>> state_topic_;
  std::optional<dds::Reader<RspState>> state_reader_;
  std::optional<HubProcess> hub_;
  fs::path hub_file_;
  std::atomic<bool> running_{true};
  std::thread worker_;
  std::mutex mutex_;
  std::vector<SeenState> states_;
};

TEST_P(HubdStaleAfterStopTest, CommandsQueuedWhileStoppedNeverActAfterTheContinue) {
  auto planner = test_support::ChildProcess::start(
      HUBRT_HUBCTL_PATH,
      {"send", "/tool_changer/command", "target_type=tool_changer", "target_name=rsp", "action=unlock",
       "--rate", "10", "--quiet", "--timeout", "20"},
      domain_->env());
  ASSERT_TRUE(planner) << planner.error().message;
  ASSERT_TRUE(wait_for_state([](const SeenState& s) {
    return s.lifecycle == kOperational && s.lock == "open";
  })) << "the planner never opened the changer\n"
      << planner->stdout_text() << planner->stderr_text() << hub_->output();
  std::this_thread::sleep_for(seconds(1));

  ASSERT_TRUE(hub_->process().signal(SIGSTOP));
  const std::int64_t stopped_wall = wall_ns();
  const auto stopped = SteadyClock::now();
  std::this_thread::sleep_for(milliseconds(300));
  ASSERT_TRUE(planner->signal(SIGKILL));  // the planner is gone: nobody commands from here on
  ASSERT_TRUE(planner->wait(seconds(10)));
  std::this_thread::sleep_until(stopped + seconds(4));
  ASSERT_TRUE(hub_->process().signal(SIGCONT));
  const auto continued = SteadyClock::now();
  std::this_thread::sleep_for(seconds(3));
  running_ = false;
  worker_.join();

  // What the hub published after the continue: stamped after the stop (it cannot stamp while
  // stopped; 100 ms of margin for the stop to take effect).
  std::vector<SeenState> after;
  for (const SeenState& s : states()) {
    if (s.stamp_ns > stopped_wall + 100'000'000) after.push_back(s);
  }
  ASSERT_GE(after.size(), 15u) << "the heartbeat (10 Hz) went on after the continue\n" << hub_->output();
  for (const SeenState& s : after) {
    const double at = std::chrono::duration<double>(s.received - continued).count();
    EXPECT_NE(s.lifecycle, kOperational)
        << "operational on a stale command, " << at << " s after the continue: " << s.describe();
    EXPECT_FALSE(s.fresh_msg) << at << " s after the continue: " << s.describe();
    EXPECT_TRUE(s.lock == "closing" || s.lock == "closed") << "the changer driven open by a 4 s old command, "
                                                           << at << " s after the continue: " << s.describe();
  }
  EXPECT_TRUE(hub_->process().wait_for_output("could not run for", seconds(1))) << "hubd reports the stall\n"
                                                                                << hub_->output();

  const SeenState& first = after.front();
  EXPECT_EQ(first.lifecycle, kSafe) << first.describe();
  const double to_safe = std::chrono::duration<double>(first.received - continued).count();
  test_support::record_time_to_safe(
      GetParam() ? "sigstop_stall_rsp" : "sigstop_stall_rsp_unsynced",
      test_support::TimeToSafe{
          GetParam() ? "SIGSTOP stall (4 s), then continued"
                     : "SIGSTOP stall (4 s), then continued, clock_tolerance_ms: none",
          "rsp_ecu", "lock valve (changer open -> closed)",
          GetParam() ? "first cycle after the continue: the command in force is 4 s old (watchdog); "
                       "the queued commands are stale by their source timestamps and discarded as "
                       "queued in the stall"
                     : "first cycle after the continue: watchdog; the queued commands are discarded "
                       "as queued in the stall (no ages without synced clocks)",
          to_safe, 0.1 + 0.1, "one period after the continue (+0.1 s for the test's reader)",
          "hubrt_hubd_stale_after_stop_test"});
  EXPECT_LE(to_safe, 0.2 + 1.0) << "generous: a loaded machine; the row records the figure";
}

INSTANTIATE_TEST_SUITE_P(Clocks, HubdStaleAfterStopTest, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool>& param) {
                           return param.param ? std::string("Synced") : std::string("NotSynced");
                         });

}  // namespace
}  // namespace hubrt::integration
