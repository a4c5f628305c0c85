// The planner goes away while it commands, with real processes: hubd runs the Dock ECU, `hubctl
// send` commands it at 10 Hz, and the planner is killed (kill -9: a crash) or stopped (SIGSTOP: a
// stalled planner, its process and its DDS threads frozen). Either way the node goes safe one
// command timeout after the last command was written, within one period (fresh_msg false, the
// lifecycle safe), measured from the kill or stop; each case writes its row of docs/safety.md.
#include <csignal>
#include <functional>
#include <thread>

#include <gtest/gtest.h>

#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/test_support/hub_process.h"
#include "hubrt/test_support/time_to_safe.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using test_support::HubProcess;
using test_support::HubProcessOptions;

using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using SteadyClock = std::chrono::steady_clock;

constexpr auto kPatience = seconds(20);  // start-up under sanitizers on a loaded 2-core machine
constexpr std::uint8_t kOperational = 3;

class HubdPlannerGoneTest : public ::testing::TestWithParam<int> {  // param: the signal
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-observer");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    topic_.emplace(*dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state"));
    reader_.emplace(*dds::Reader<DockState>::create(*participant_, *topic_));
    auto hub = HubProcess::start(*domain_, HubProcessOptions{});
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
  }
  // The first State (taken from now on) that satisfies `done`; when it arrived.
  std::optional<SteadyClock::time_point> first(const std::function<bool(const DockState&)>& done) {
    const auto deadline = SteadyClock::now() + kPatience;
    while (SteadyClock::now() < deadline) {
      while (reader_->take_next(sample_).value_or(false)) {
        if (done(sample_.get())) return SteadyClock::now();
      }
      std::this_thread::sleep_for(milliseconds(1));
    }
    return std::nullopt;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> topic_;
  std::optional<dds::Reader<DockState>> reader_;
  std::optional<HubProcess> hub_;
  dds::Sample<DockState> sample_;
};

TEST_P(HubdPlannerGoneTest, TheNodeGoesSafeOneTimeoutAfterTheLastCommand) {
  auto planner =
      test_support::ChildProcess::start(HUBRT_HUBCTL_PATH,
                                        {"send", "/dock/command", "target_type=dock", "target_name=dock",
                                         "action=monitor", "--rate", "10", "--quiet", "--timeout", "20"},
                                        domain_->env());
  ASSERT_TRUE(planner) << planner.error().message;
  ASSERT_TRUE(first([](const DockState& s) { return s.fresh_msg && s.header.lifecycle == kOperational; }))
      << hub_->output();
  std::this_thread::sleep_for(seconds(1));
  ASSERT_TRUE(planner->signal(GetParam()));
  const auto gone = SteadyClock::now();
  const auto safe =
      first([](const DockState& s) { return !s.fresh_msg && s.header.lifecycle != kOperational; });
  ASSERT_TRUE(safe) << "the node never went safe\n" << hub_->output();
  const double to_safe = std::chrono::duration<double>(*safe - gone).count();
  // The last command was written up to one planner period (0.1 s) before the signal; the hub sees
  // the lapse in its next cycle (0.1 s). Generous above for a loaded machine; the row keeps the figure.
  EXPECT_GT(to_safe, 0.85);
  EXPECT_LT(to_safe, 1.0 + 0.1 + 0.5);
  const bool crash = GetParam() == SIGKILL;
  test_support::record_time_to_safe(
      crash ? "planner_crash_dock" : "planner_stall_dock",
      test_support::TimeToSafe{crash ? "planner crash (kill -9)" : "planner stall (SIGSTOP)", "dock_ecu",
                               "none (dock sensors only): lifecycle safe",
                               "command watchdog: no command younger than the timeout", to_safe,
                               1.0 + 0.1 + 0.1, "command timeout + one period (+0.1 s reader)",
                               "hubrt_hubd_planner_gone_test"});
}

INSTANTIATE_TEST_SUITE_P(Planner, HubdPlannerGoneTest, ::testing::Values(SIGKILL, SIGSTOP),
                         [](const ::testing::TestParamInfo<int>& param) {
                           return param.param == SIGKILL ? std::string("Killed") : std::string("Stopped");
                         });

}  // namespace
}  // namespace hubrt::integration
