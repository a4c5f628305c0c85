// hubd ends safely on every way out a signal gives it: the RSP ECU holds its lock valve energised
// (changer open) for a live planner, then a signal arrives. Every catchable terminating signal
// must drive the valve safe (de-energised) before hubd exits with its documented status
// (hubrt/base/exit_codes.h), seen from outside on /sim/rsp_ecu/signals, where the sim bridge
// publishes the outputs one last time after the safe state. SIGPIPE, and stderr closed under a
// running hub, must not stop it at all.
#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>

#include <atomic>
#include <csignal>
#include <cstring>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "hubrt/base/exit_codes.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"

#include "dock_messages.h"
#include "hub_process.h"
#include "rsp_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using rsp_ecu::RspCommand;
using std::chrono::milliseconds;
using Signals = hub_msgs_msg_dds__SimSignals_;

// Generous: a busy 2-core machine running sanitizer builds in parallel. These tests check
// behaviour, not timing.
constexpr auto kPatience = std::chrono::seconds(20);

// The level of output `name` in one SimSignals sample, if it is there.
std::optional<bool> output_level(const Signals& signals, std::string_view name) {
  for (std::uint32_t i = 0; i < signals.signals._length; ++i) {
    const auto& s = signals.signals._buffer[i];
    if (s.name != nullptr && name == s.name && s.output) return s.active;
  }
  return std::nullopt;
}

// hubd running the RSP ECU with its lock valve held open by the test's planner.
class HubdWithOpenChanger : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-planner");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    auto dock_topic = dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state");
    ASSERT_TRUE(dock_topic) << dock_topic.error().message;
    dock_topic_.emplace(std::move(*dock_topic));
    auto dock_writer = dds::Writer<DockState>::create(*participant_, *dock_topic_);
    ASSERT_TRUE(dock_writer) << dock_writer.error().message;
    dock_writer_.emplace(std::move(*dock_writer));
    auto command_topic = dds::Topic<RspCommand>::create(*participant_, "/tool_changer/command");
    ASSERT_TRUE(command_topic) << command_topic.error().message;
    command_topic_.emplace(std::move(*command_topic));
    auto command_writer = dds::Writer<RspCommand>::create(*participant_, *command_topic_);
    ASSERT_TRUE(command_writer) << command_writer.error().message;
    command_writer_.emplace(std::move(*command_writer));
    auto signals_topic = dds::Topic<Signals>::create(*participant_, sim::sim_signals_topic("rsp_ecu"));
    ASSERT_TRUE(signals_topic) << signals_topic.error().message;
    signals_topic_.emplace(std::move(*signals_topic));
    auto signals_reader = dds::Reader<Signals>::create(*participant_, *signals_topic_);
    ASSERT_TRUE(signals_reader) << signals_reader.error().message;
    signals_reader_.emplace(std::move(*signals_reader));

    HubProcessOptions options;
    options.hub = "rsp_ecu";
    auto hub = HubProcess::start(*domain_, options);
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
    ASSERT_TRUE(command_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    ASSERT_TRUE(dock_writer_->wait_for_readers(1, kPatience)) << hub_->output();
    planner_ = std::thread([this] { plan(); });
  }

  void TearDown() override {
    running_ = false;
    if (planner_.joinable()) planner_.join();
  }

  // The planner wants the changer open, and the Dock ECU reports the smart tool home, every 50 ms
  // until the test ends: only hubd itself can close the valve.
  void plan() {
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
    RspCommand unlock{};
    hubrt::msgs::typed::assign(unlock.target_type, "tool_changer");
    hubrt::msgs::typed::assign(unlock.target_name, "rsp");
    hubrt::msgs::typed::assign(unlock.action, "unlock");
    hubrt::msgs::typed::assign(unlock.gripper, "grab");
    while (running_) {
      dock_writer_->write(dock).ignore();
      command_writer_->write(unlock).ignore();
      std::this_thread::sleep_for(milliseconds(50));
    }
  }

  // Takes signal samples until rsp.lock_valve is at `level`; false after the patience runs out.
  bool wait_for_lock_valve(bool level) {
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      const Result<bool> taken = signals_reader_->take_next(signals_);
      if (!taken.is_ok() || !taken.value()) {
        std::this_thread::sleep_for(milliseconds(2));
        continue;
      }
      if (output_level(signals_.get(), "rsp.lock_valve") == level) return true;
    }
    return false;
  }

  // The lock valve's level in the last signals sample hubd published (after it exited).
  std::optional<bool> last_lock_valve_level() {
    std::optional<bool> last;
    while (true) {
      const Result<bool> taken = signals_reader_->take_next(signals_);
      if (!taken.is_ok() || !taken.value()) return last;
      last = output_level(signals_.get(), "rsp.lock_valve");
    }
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> dock_topic_;
  std::optional<dds::Writer<DockState>> dock_writer_;
  std::optional<dds::Topic<RspCommand>> command_topic_;
  std::optional<dds::Writer<RspCommand>> command_writer_;
  std::optional<dds::Topic<Signals>> signals_topic_;
  std::optional<dds::Reader<Signals>> signals_reader_;
  dds::Sample<Signals> signals_;
  std::optional<HubProcess> hub_;
  std::thread planner_;
  std::atomic<bool> running_{true};
};

class HubdExitSignalsTest : public HubdWithOpenChanger, public ::testing::WithParamInterface<int> {};

// Old hubd: SIGHUP/SIGQUIT/SIGUSR1... killed it at once (status "killed by signal"), the valve
// left energised; only SIGTERM/SIGINT were handled.
TEST_P(HubdExitSignalsTest, DrivesTheOutputsSafeThenExitsWithTheDocumentedStatus) {
  const int signal = GetParam();
  ASSERT_TRUE(wait_for_lock_valve(true)) << "the changer never opened\n" << hub_->output();
  ASSERT_TRUE(hub_->process().signal(signal));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::for_stop_signal(signal)))
      << sigdescr_np(signal) << ": " << status->describe() << "\n"
      << hub_->output();
  EXPECT_EQ(last_lock_valve_level(), std::optional<bool>(false))
      << sigdescr_np(signal) << ": the last outputs published are not safe\n"
      << hub_->output();
  EXPECT_NE(hub_->output().find(
                fmt::format("stopping on SIG{}: outputs driven to their safe state", sigabbrev_np(signal))),
            std::string::npos)
      << hub_->output();
}

INSTANTIATE_TEST_SUITE_P(Signals, HubdExitSignalsTest,
                         ::testing::Values(SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string("SIG") + sigabbrev_np(param.param);
                         });

// SIGPIPE is what a write to a closed pipe raises: ignored, the hub keeps its cycle and its outputs
// (old hubd died of it, status "killed by signal 13").
TEST_F(HubdWithOpenChanger, IgnoresSigpipe) {
  ASSERT_TRUE(wait_for_lock_valve(true)) << "the changer never opened\n" << hub_->output();
  ASSERT_TRUE(hub_->process().signal(SIGPIPE));
  // Still cycling with the valve as commanded: ten more samples (a second at 10 Hz).
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(wait_for_lock_valve(true)) << i << "\n" << hub_->output();
  ASSERT_TRUE(hub_->process().signal(SIGTERM));
  auto status = hub_->process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::kOk)) << status->describe() << "\n" << hub_->output();
}

}  // namespace
}  // namespace hubrt::integration
