// A planner that flips its command floods nobody (issue 11): a real hubd (Tool ECU on the fake
// HAL) and two writers alternating the smart tool's command between "idle" and "inhibit" as fast
// as they can. Before the budget of immediate States every change published a State at once
// (5,420 States/s from one hub); now the tool's State rate stays within the budget's token bucket
// (a burst of 4, then one immediate State per immediate_state_interval_ms, 10 ms) plus the
// heartbeat, the heartbeat keeps its period, the last command is echoed, and /diagnostics counts
// the held-back States and publishes the bucket.
#include <atomic>
#include <cstdio>
#include <map>
#include <optional>
#include <thread>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/assembly/diagnostics_stage.h"
#include "hubrt/dds/reader.h"
#include "hubrt/dds/sample.h"
#include "hubrt/dds/topic.h"
#include "hubrt/dds/writer.h"
#include "hubrt/msgs/typed.h"
#include "hubrt/test_support/hub_process.h"

#include "tool_messages.h"

namespace hubrt::integration {
using test_support::HubProcess;
using test_support::HubProcessOptions;
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;
using tool_ecu::SmartToolCommand;
using tool_ecu::SmartToolState;
using DiagnosticArray = diagnostic_msgs_msg_dds__DiagnosticArray_;

// Generous: a busy 2-core machine running sanitizer builds of several engineers at once.
constexpr auto kPatience = seconds(20);
constexpr double kPeriodS = 0.1;    // tool_ecu.yaml: rate_hz 10
constexpr double kBudgetS = 0.010;  // immediate_state_interval_ms default
constexpr double kBurst = 4;        // runtime::kDefaultImmediateStateBurst
constexpr double kFloodS = 3.0;

double stamp_s(const SmartToolState& s) {
  return s.header.stamp.sec + s.header.stamp.nanosec * 1e-9;
}

// One planner: its own participant and writer, as two separate planner processes would be.
struct Planner {
  static Planner create(const test_support::TestDomain& domain, const char* name) {
    auto participant = dds::Participant::create(domain.config(), name);
    EXPECT_TRUE(participant) << participant.error().message;
    Planner p{std::move(*participant), std::nullopt, std::nullopt};
    auto topic = dds::Topic<SmartToolCommand>::create(p.participant, "/smart_tool/command");
    EXPECT_TRUE(topic) << topic.error().message;
    p.topic.emplace(std::move(*topic));
    auto writer = dds::Writer<SmartToolCommand>::create(p.participant, *p.topic);
    EXPECT_TRUE(writer) << writer.error().message;
    p.writer.emplace(std::move(*writer));
    return p;
  }
  bool send(const char* action) {
    SmartToolCommand c{};
    hubrt::msgs::typed::assign(c.target_type, "smart_tool");
    hubrt::msgs::typed::assign(c.target_name, "tool");
    hubrt::msgs::typed::assign(c.action, action);
    hubrt::msgs::typed::assign(c.program, "");
    return writer->write(c).is_ok();
  }
  dds::Participant participant;
  std::optional<dds::Topic<SmartToolCommand>> topic;
  std::optional<dds::Writer<SmartToolCommand>> writer;
};

// The value of `key` in status `status_name` of a DiagnosticArray, if there.
std::optional<std::string> diagnostic_value(const DiagnosticArray& a, const std::string& status_name,
                                            const std::string& key) {
  for (std::uint32_t i = 0; i < a.status._length; ++i) {
    const auto& s = a.status._buffer[i];
    if (s.name == nullptr || status_name != s.name) continue;
    for (std::uint32_t k = 0; k < s.values._length; ++k) {
      if (s.values._buffer[k].key != nullptr && key == s.values._buffer[k].key)
        return std::string(s.values._buffer[k].value);
    }
  }
  return std::nullopt;
}

TEST(CommandFlood, TwoPlannersFlippingTheCommandStayWithinTheBudgetAndTheHeartbeatGoesOn) {
  auto domain = test_support::TestDomain::acquire();
  ASSERT_TRUE(domain) << domain.error().message;
  auto participant = dds::Participant::create(domain->config(), "test-observer");
  ASSERT_TRUE(participant) << participant.error().message;
  auto state_topic = dds::Topic<SmartToolState>::create(*participant, "/tool_ecu/tool/state");
  ASSERT_TRUE(state_topic) << state_topic.error().message;
  auto states = dds::Reader<SmartToolState>::create(*participant, *state_topic);
  ASSERT_TRUE(states) << states.error().message;
  auto diag_topic = dds::Topic<DiagnosticArray>::create(*participant, "/diagnostics");
  ASSERT_TRUE(diag_topic) << diag_topic.error().message;
  auto diagnostics = dds::Reader<DiagnosticArray>::create(*participant, *diag_topic);
  ASSERT_TRUE(diagnostics) << diagnostics.error().message;

  HubProcessOptions options;
  options.hub = "tool_ecu";
  auto hub = HubProcess::start(*domain, options);
  ASSERT_TRUE(hub) << hub.error().message;
  ASSERT_TRUE(states->wait_for_writers(1, kPatience)) << hub->output();
  Planner a = Planner::create(*domain, "planner-a");
  Planner b = Planner::create(*domain, "planner-b");
  ASSERT_TRUE(a.writer->wait_for_readers(1, kPatience));
  ASSERT_TRUE(b.writer->wait_for_readers(1, kPatience));

  // Each State by sequence number (the reader's history may drop some; seq says how many were
  // published), with the hub's stamp, so rates are measured on the hub's clock, not on arrival.
  std::map<std::uint64_t, double> stamps;
  std::map<std::uint64_t, std::string> echoes;
  dds::Sample<SmartToolState> sample;
  const auto take_all = [&] {
    while (true) {
      const Result<bool> taken = states->take_next(sample);
      if (!taken.is_ok() || !taken.value()) return;
      stamps[sample.get().header.seq] = stamp_s(sample.get());
      echoes[sample.get().header.seq] = std::string(sample.get().echo.action);
    }
  };

  std::atomic<bool> flooding{true};
  std::atomic<std::uint64_t> writes{0};
  const auto flood = [&](Planner& p, bool start_idle) {
    bool idle = start_idle;
    while (flooding.load()) {
      if (p.send(idle ? "idle" : "inhibit")) writes.fetch_add(1);
      idle = !idle;
    }
  };
  take_all();
  const std::uint64_t seq_before = stamps.empty() ? 0 : stamps.rbegin()->first;
  std::thread writer_a(flood, std::ref(a), true);
  std::thread writer_b(flood, std::ref(b), false);
  const auto flood_end = std::chrono::steady_clock::now() + std::chrono::duration<double>(kFloodS);
  while (std::chrono::steady_clock::now() < flood_end) {
    take_all();
    std::this_thread::sleep_for(milliseconds(1));
  }
  flooding = false;
  writer_a.join();
  writer_b.join();
  // The last word: one planner settles on "inhibit"; the next States must echo it. First every
  // flood sample must have reached the hub: two writers' samples are not ordered with each other,
  // and on a loaded machine b's last "idle" could otherwise arrive after a's final word.
  ASSERT_TRUE(a.writer->untyped().wait_for_acks(seconds(10)));
  ASSERT_TRUE(b.writer->untyped().wait_for_acks(seconds(10)));
  ASSERT_TRUE(a.send("inhibit"));
  const auto settle_end = std::chrono::steady_clock::now() + seconds(1);
  while (std::chrono::steady_clock::now() < settle_end) {
    take_all();
    std::this_thread::sleep_for(milliseconds(1));
  }

  const double write_rate = static_cast<double>(writes.load()) / kFloodS;
  // The flood must really exceed the budget several times over, or the test proves nothing
  // (before the budget the hub published one State per change).
  ASSERT_GT(write_rate, 3 * (1 / kBudgetS + 1 / kPeriodS)) << "the writers could not flood on this machine";

  // States published during the flood, on the hub's clock: from the first State after the flood
  // began to the last one before it ended (the seq range counts the ones the reader missed).
  std::vector<std::pair<std::uint64_t, double>> during;
  for (const auto& [seq, t] : stamps) {
    if (seq > seq_before + 1) during.emplace_back(seq, t);
  }
  ASSERT_GT(during.size(), 10U) << hub->output();
  // Leave out the last second (the settle phase) by the hub's stamps.
  const double flood_begin_s = during.front().second;
  while (!during.empty() && during.back().second > flood_begin_s + kFloodS - 0.2) during.pop_back();
  ASSERT_GT(during.size(), 10U);
  const double span_s = during.back().second - during.front().second;
  const double published = static_cast<double>(during.back().first - during.front().first);
  const double state_rate = published / span_s;
  std::printf("flood: %.0f commands/s written, %.1f States/s published over %.2f s\n", write_rate, state_rate,
              span_s);
  // At most the burst plus one immediate State per 10 ms, and one heartbeat per 100 ms: 110/s.
  // The budget is exact on the hub's own clock; +2 States for the edges of the window.
  EXPECT_LE(published, span_s * (1 / kBudgetS + 1 / kPeriodS) + kBurst + 2)
      << state_rate << " States/s while planners wrote " << write_rate << " commands/s";

  // The heartbeat keeps its period: no two consecutive States further apart than a period, plus
  // generous slack for a loaded machine (the cycle thread may be woken late).
  double worst_gap_s = 0;
  for (std::size_t i = 1; i < during.size(); ++i) {
    if (during[i].first == during[i - 1].first + 1)
      worst_gap_s = std::max(worst_gap_s, during[i].second - during[i - 1].second);
  }
  EXPECT_LE(worst_gap_s, kPeriodS + 0.15) << "a State gap longer than the heartbeat period";

  // The latest command wins: the last States echo the final "inhibit".
  ASSERT_FALSE(echoes.empty());
  EXPECT_EQ(echoes.rbegin()->second, "inhibit");

  // /diagnostics counts the held-back States, for the node and the hub (published at 1 Hz). The
  // counts are cumulative, and the reader still holds arrays published during the flood (oldest
  // first; once, under load, one of 67 was taken for the whole flood's): read on until two arrays
  // in a row give the same count, which is then the whole flood's.
  std::optional<std::string> node_deferred;
  std::optional<std::string> hub_deferred;
  dds::Sample<DiagnosticArray> diag;
  bool settled = false;
  const auto diag_end = std::chrono::steady_clock::now() + kPatience;
  while (std::chrono::steady_clock::now() < diag_end && !settled) {
    const Result<bool> taken = diagnostics->take_next(diag);
    if (!taken.is_ok() || !taken.value()) {
      std::this_thread::sleep_for(milliseconds(10));
      continue;
    }
    const auto node = diagnostic_value(diag.get(), "tool_ecu: tool", "states_deferred");
    const auto hub_count = diagnostic_value(diag.get(), "tool_ecu: cycle", "states_deferred");
    if (!node || !hub_count || std::stoull(*node) == 0) continue;  // from before the flood
    settled = node_deferred && *node_deferred == *node;
    node_deferred = node;
    hub_deferred = hub_count;
  }
  ASSERT_TRUE(node_deferred) << "no /diagnostics with the tool's states_deferred";
  ASSERT_TRUE(hub_deferred);
  EXPECT_TRUE(settled) << "the tool's states_deferred still grew after the flood: " << *node_deferred;
  EXPECT_GT(std::stoull(*node_deferred), 100U);
  EXPECT_GE(std::stoull(*hub_deferred), std::stoull(*node_deferred));
  const auto interval = diagnostic_value(diag.get(), "tool_ecu: cycle", "immediate_state_interval_ms");
  ASSERT_TRUE(interval);
  EXPECT_EQ(std::stod(*interval), 10.0);
  const auto burst = diagnostic_value(diag.get(), "tool_ecu: cycle", "immediate_state_burst");
  ASSERT_TRUE(burst) << "/diagnostics publishes the bucket's size";
  EXPECT_EQ(std::stod(*burst), kBurst);
}

}  // namespace
}  // namespace hubrt::integration
