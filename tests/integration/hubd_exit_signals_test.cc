// hubd ends safely on every way out a signal gives it: the RSP ECU holds its lock valve energised
// (changer open) for a live planner, then a signal arrives. Every catchable terminating signal
// must drive the valve safe (de-energised) before hubd exits with its documented status
// (hubrt/base/exit_codes.h), seen from outside on /sim/rsp_ecu/signals, where the sim bridge
// publishes the outputs one last time after the safe state. SIGPIPE, and stderr closed under a
// running hub, must not stop it at all.
#include <fcntl.h>
#include <spawn.h>
#include <unistd.h>

#include <array>
#include <csignal>
#include <cstring>
#include <memory>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <sys/wait.h>

#include "hubrt/base/exit_codes.h"
#include "hubrt/dds/sample.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/sim/sim_bridge_stage.h"
#include "hubrt/test_support/hub_under_test.h"

#include "dock_messages.h"
#include "rsp_messages.h"

namespace hubrt::integration {
namespace {

using dock_ecu::DockState;
using rsp_ecu::RspCommand;
using std::chrono::milliseconds;
using test_support::HubUnderTest;
using test_support::StateStream;
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

// What the planner and the stand-in Dock ECU write: the changer open, the smart tool home.
struct OpenChangerOrders {
  OpenChangerOrders() {
    hubrt::msgs::typed::assign(dock.name, "dock");
    hubrt::msgs::typed::assign(dock.echo.target_type, "");
    hubrt::msgs::typed::assign(dock.echo.target_name, "");
    hubrt::msgs::typed::assign(dock.echo.action, "");
    dock.slots._buffer = slots.data();
    dock.slots._length = static_cast<std::uint32_t>(slots.size());
    dock.slots._maximum = dock.slots._length;
    hubrt::msgs::typed::assign(unlock.target_type, "tool_changer");
    hubrt::msgs::typed::assign(unlock.target_name, "rsp");
    hubrt::msgs::typed::assign(unlock.action, "unlock");
    hubrt::msgs::typed::assign(unlock.gripper, "grab");
  }
  OpenChangerOrders(const OpenChangerOrders&) = delete;
  OpenChangerOrders& operator=(const OpenChangerOrders&) = delete;

  std::array<hub_msgs_msg_dds__DockSlot_, 3> slots{
      {{"ladder_frame_tool", true}, {"filter_tool", true}, {"smart_tool", true}}};
  DockState dock{};
  RspCommand unlock{};
};

// hubd running the RSP ECU with its lock valve held open by the test's planner.
class HubdWithOpenChanger : public ::testing::Test {
 protected:
  void SetUp() override {
    ASSERT_NO_FATAL_FAILURE(hub_.open());
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(dock_, "/dock_ecu/dock/state"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_writer(commands_, "/tool_changer/command"));
    ASSERT_NO_FATAL_FAILURE(hub_.make_stream(signals_, sim::sim_signals_topic("rsp_ecu")));
    ASSERT_NO_FATAL_FAILURE(hub_.start({.hub = "rsp_ecu"}));
    // The planner wants the changer open, and the Dock ECU reports the smart tool home, every 50 ms
    // until the test ends: only hubd itself can close the valve.
    hub_.plan([this, orders = std::make_shared<OpenChangerOrders>()] {
      dock_->write(orders->dock).ignore();
      commands_->write(orders->unlock).ignore();
    });
  }

  // Takes signal samples until rsp.lock_valve is at `level`; false after the patience runs out.
  bool wait_for_lock_valve(bool level) {
    return signals_->take_until(
        [level](const Signals& s) { return output_level(s, "rsp.lock_valve") == level; }, kPatience);
  }

  // The lock valve's level in the last signals sample hubd published (after it exited).
  std::optional<bool> last_lock_valve_level() {
    std::optional<bool> last;
    dds::Sample<Signals> signals;
    while (true) {
      const Result<bool> taken = signals_->reader().take_next(signals);
      if (!taken.is_ok() || !taken.value()) return last;
      last = output_level(signals.get(), "rsp.lock_valve");
    }
  }

  dds::Writer<DockState>* dock_ = nullptr;
  dds::Writer<RspCommand>* commands_ = nullptr;
  StateStream<Signals>* signals_ = nullptr;
  HubUnderTest hub_{kPatience};
};

class HubdExitSignalsTest : public HubdWithOpenChanger, public ::testing::WithParamInterface<int> {};

// Old hubd: SIGHUP/SIGQUIT/SIGUSR1... killed it at once (status "killed by signal"), the valve
// left energised; only SIGTERM/SIGINT were handled.
TEST_P(HubdExitSignalsTest, DrivesTheOutputsSafeThenExitsWithTheDocumentedStatus) {
  const int signal = GetParam();
  ASSERT_TRUE(wait_for_lock_valve(true)) << "the changer never opened\n" << hub_.output();
  ASSERT_TRUE(hub_.hub().process().signal(signal));
  auto status = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::for_stop_signal(signal)))
      << sigdescr_np(signal) << ": " << status->describe() << "\n"
      << hub_.output();
  EXPECT_EQ(last_lock_valve_level(), std::optional<bool>(false))
      << sigdescr_np(signal) << ": the last outputs published are not safe\n"
      << hub_.output();
  EXPECT_NE(hub_.output().find(
                fmt::format("stopping on SIG{}: outputs driven to their safe state", sigabbrev_np(signal))),
            std::string::npos)
      << hub_.output();
}

INSTANTIATE_TEST_SUITE_P(Signals, HubdExitSignalsTest,
                         ::testing::Values(SIGTERM, SIGINT, SIGHUP, SIGQUIT, SIGUSR1, SIGUSR2, SIGALRM),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return std::string("SIG") + sigabbrev_np(param.param);
                         });

// SIGPIPE is what a write to a closed pipe raises: ignored, the hub keeps its cycle and its outputs
// (old hubd died of it, status "killed by signal 13").
TEST_F(HubdWithOpenChanger, IgnoresSigpipe) {
  ASSERT_TRUE(wait_for_lock_valve(true)) << "the changer never opened\n" << hub_.output();
  ASSERT_TRUE(hub_.hub().process().signal(SIGPIPE));
  // Still cycling with the valve as commanded: ten more samples (a second at 10 Hz).
  for (int i = 0; i < 10; ++i) ASSERT_TRUE(wait_for_lock_valve(true)) << i << "\n" << hub_.output();
  ASSERT_TRUE(hub_.hub().process().signal(SIGTERM));
  auto status = hub_.hub().process().wait(kPatience);
  ASSERT_TRUE(status) << status.error().message;
  EXPECT_TRUE(status->exited_with(exit_codes::kOk)) << status->describe() << "\n" << hub_.output();
}

}  // namespace
}  // namespace hubrt::integration
