// Planners whose clocks are 10 s off the hub's, with real processes: hubd runs the Dock ECU and
// `hubctl send --stamp-offset` stamps every command's DDS source timestamp 10 s in the past (a
// planner whose clock is behind: its commands look 10 s old and never act) or 10 s in the future
// (rejected, the skew named in error_list). /diagnostics shows the stale and rejected commands and
// the clock offset seen. The same command without an offset acts: the setup itself is sound.
#include <csignal>
#include <functional>
#include <optional>
#include <string>
#include <thread>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/test_support/hub_process.h"

#include "dock_messages.h"

namespace hubrt::integration {
namespace {

using test_support::HubProcess;
using test_support::HubProcessOptions;

using dock_ecu::DockState;
using std::chrono::milliseconds;
using std::chrono::seconds;
using Diagnostics = diagnostic_msgs_msg_dds__DiagnosticArray_;

// Generous: start-up under sanitizers on a loaded 2-core machine; /diagnostics comes at 1 Hz.
constexpr auto kPatience = seconds(20);
constexpr std::uint8_t kOperational = 3;

std::optional<std::string> value_of(const Diagnostics& array, std::string_view name, std::string_view key) {
  for (std::uint32_t i = 0; i < array.status._length; ++i) {
    const auto& status = array.status._buffer[i];
    if (status.name == nullptr || std::string_view(status.name) != name) continue;
    for (std::uint32_t k = 0; k < status.values._length; ++k) {
      const auto& pair = status.values._buffer[k];
      if (pair.key != nullptr && key == pair.key) return std::string(pair.value);
    }
  }
  return std::nullopt;
}

std::string errors_of(const DockState& s) {
  std::string out;
  for (std::uint32_t i = 0; i < s.error_list._length; ++i) out += std::string(s.error_list._buffer[i]) + "; ";
  return out;
}

class HubdClockSkewTest : public ::testing::Test {
 protected:
  void SetUp() override {
    auto domain = test_support::TestDomain::acquire();
    ASSERT_TRUE(domain) << domain.error().message;
    domain_.emplace(std::move(*domain));
    auto participant = dds::Participant::create(domain_->config(), "test-observer");
    ASSERT_TRUE(participant) << participant.error().message;
    participant_.emplace(std::move(*participant));
    state_topic_.emplace(*dds::Topic<DockState>::create(*participant_, "/dock_ecu/dock/state"));
    state_reader_.emplace(*dds::Reader<DockState>::create(*participant_, *state_topic_));
    diagnostics_topic_.emplace(*dds::Topic<Diagnostics>::create(*participant_, "/diagnostics"));
    diagnostics_reader_.emplace(*dds::Reader<Diagnostics>::create(*participant_, *diagnostics_topic_));
    auto hub = HubProcess::start(*domain_, HubProcessOptions{});
    ASSERT_TRUE(hub) << hub.error().message;
    hub_.emplace(std::move(*hub));
  }

  test_support::ChildProcess start_planner(const std::string& stamp_offset) {
    std::vector<std::string> args = {"send",
                                     "/dock/command",
                                     "target_type=dock",
                                     "target_name=dock",
                                     "action=monitor",
                                     "--rate",
                                     "10",
                                     "--quiet",
                                     "--timeout",
                                     "20"};
    if (!stamp_offset.empty()) args.insert(args.end(), {"--stamp-offset", stamp_offset});
    auto planner = test_support::ChildProcess::start(HUBRT_HUBCTL_PATH, args, domain_->env());
    EXPECT_TRUE(planner) << planner.error().message;
    return std::move(*planner);
  }

  // Watches the States for `span`: fails on any that is fresh or operational; returns the last.
  DockState watch_never_acting(Duration span) {
    DockState last{};
    std::uint32_t seen = 0;
    const auto end = std::chrono::steady_clock::now() + span;
    while (std::chrono::steady_clock::now() < end) {
      while (state_reader_->take_next(state_).value_or(false)) {
        const DockState& s = state_.get();
        ++seen;
        EXPECT_FALSE(s.fresh_msg) << errors_of(s);
        EXPECT_NE(s.header.lifecycle, kOperational) << errors_of(s);
        last = s;
        last_errors_ = errors_of(s);
      }
      std::this_thread::sleep_for(milliseconds(5));
    }
    EXPECT_GT(seen, 10u) << "the heartbeat";
    return last;
  }

  // The latest value of `key` of the dock node's /diagnostics status, once `done` holds for it.
  std::optional<std::string> diagnostics_until(std::string_view key,
                                               const std::function<bool(const std::string&)>& done) {
    std::optional<std::string> value;
    const auto deadline = std::chrono::steady_clock::now() + kPatience;
    while (std::chrono::steady_clock::now() < deadline) {
      while (diagnostics_reader_->take_next(diagnostics_).value_or(false)) {
        value = value_of(diagnostics_.get(), "dock_ecu: dock", key);
        if (value && done(*value)) return value;
      }
      std::this_thread::sleep_for(milliseconds(20));
    }
    return value;
  }

  std::optional<test_support::TestDomain> domain_;
  std::optional<dds::Participant> participant_;
  std::optional<dds::Topic<DockState>> state_topic_;
  std::optional<dds::Reader<DockState>> state_reader_;
  std::optional<dds::Topic<Diagnostics>> diagnostics_topic_;
  std::optional<dds::Reader<Diagnostics>> diagnostics_reader_;
  std::optional<HubProcess> hub_;
  dds::Sample<DockState> state_;
  dds::Sample<Diagnostics> diagnostics_;
  std::string last_errors_;
};

TEST_F(HubdClockSkewTest, APlannerTenSecondsBehindNeverActs) {
  auto planner = start_planner("-10");
  ASSERT_TRUE(diagnostics_until("commands_stale", [](const std::string& v) { return v != "0"; }))
      << "no stale command counted\n"
      << hub_->output();
  watch_never_acting(seconds(2));
  EXPECT_NE(last_errors_.find("stale command: written 10."), std::string::npos) << last_errors_;
  const auto offset =
      diagnostics_until("clock_offset_max_ms", [](const std::string& v) { return std::stod(v) > 9000.0; });
  ASSERT_TRUE(offset);
  EXPECT_GT(std::stod(*offset), 9000.0) << "the skew shown in /diagnostics";
  EXPECT_LT(std::stod(*offset), 11000.0);
  EXPECT_TRUE(hub_->process().wait_for_output("stale command", seconds(1))) << "and logged";
}

TEST_F(HubdClockSkewTest, APlannerTenSecondsAheadIsRejectedWithTheReason) {
  auto planner = start_planner("10");
  ASSERT_TRUE(diagnostics_until("commands_rejected", [](const std::string& v) { return v != "0"; }))
      << "no rejection counted\n"
      << hub_->output();
  watch_never_acting(seconds(2));
  // 10 s ahead less the command's way to the hub: "10.000 s" on a quiet host, "9.996 s" seen in a
  // CI run with a build beside the tests.
  const std::string stamped = "rejected command: stamped ";
  const auto at = last_errors_.find(stamped);
  ASSERT_NE(at, std::string::npos) << last_errors_;
  const double ahead_s = std::stod(last_errors_.substr(at + stamped.size()));
  EXPECT_GT(ahead_s, 9.0) << last_errors_;
  EXPECT_LE(ahead_s, 10.05) << last_errors_;
  EXPECT_NE(last_errors_.find("in the future, beyond the clock tolerance (50 ms)"), std::string::npos)
      << last_errors_;
  const auto offset =
      diagnostics_until("clock_offset_max_ms", [](const std::string& v) { return std::stod(v) < -9000.0; });
  ASSERT_TRUE(offset);
  EXPECT_LT(std::stod(*offset), -9000.0);
}

TEST_F(HubdClockSkewTest, WithoutAnOffsetTheSameCommandActs) {
  auto planner = start_planner("");
  const auto deadline = std::chrono::steady_clock::now() + kPatience;
  bool acted = false;
  while (!acted && std::chrono::steady_clock::now() < deadline) {
    while (state_reader_->take_next(state_).value_or(false)) {
      acted |= state_.get().fresh_msg && state_.get().header.lifecycle == kOperational;
    }
    std::this_thread::sleep_for(milliseconds(10));
  }
  EXPECT_TRUE(acted) << hub_->output();
}

}  // namespace
}  // namespace hubrt::integration
