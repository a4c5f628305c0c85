// The pure rules of the twin guard: which hub is the later one, which topics are a hub's States,
// and what the nodes report over time (manual time).
#include "hubrt/assembly/twin_rules.h"

#include <gtest/gtest.h>

namespace hubrt::assembly {
namespace {

using std::chrono::milliseconds;
using std::chrono::seconds;

dds::Guid guid(std::uint8_t first) {
  dds::Guid g;
  g.bytes[0] = first;
  g.bytes[15] = 0xc1;
  return g;
}

dds::WatchedWriter writer(const char* topic, std::uint8_t participant, const char* host, const char* pid,
                          const std::string& user_data) {
  dds::WatchedWriter w;
  w.topic_name = topic;
  w.participant_key = guid(participant);
  w.key = guid(participant);
  w.key.bytes[14] = static_cast<std::uint8_t>(w.topic_name.size());
  w.host = host;
  w.pid = pid;
  w.user_data = user_data;
  return w;
}

TEST(TwinRules, TheHubThatStartedLaterIsTheLaterOne) {
  const HubStamp early{1'000, guid(9)};
  const HubStamp late{2'000, guid(1)};
  EXPECT_TRUE(is_later(late, early));
  EXPECT_FALSE(is_later(early, late));
}

TEST(TwinRules, AtTheSameInstantTheLargerGuidIsTheLaterOneAndBothAgree) {
  const HubStamp a{5'000, guid(1)};
  const HubStamp b{5'000, guid(2)};
  EXPECT_TRUE(is_later(b, a));
  EXPECT_FALSE(is_later(a, b));
  EXPECT_FALSE(is_later(a, a));
}

TEST(TwinRules, TheStartStampRoundTripsThroughUserData) {
  EXPECT_EQ(start_stamp_user_data(1'732'000'000'123'456'789), "hubrt.started_ns=1732000000123456789;");
  EXPECT_EQ(parse_start_stamp(start_stamp_user_data(42)), 42);
  EXPECT_EQ(parse_start_stamp("enclave=/;hubrt.started_ns=7;"), 7);  // beside ROS 2's own pairs
}

TEST(TwinRules, UserDataWithoutAWellFormedStampIsNoHub) {
  EXPECT_EQ(parse_start_stamp(""), std::nullopt);
  EXPECT_EQ(parse_start_stamp("enclave=/;"), std::nullopt);
  EXPECT_EQ(parse_start_stamp("hubrt.started_ns=;"), std::nullopt);
  EXPECT_EQ(parse_start_stamp("hubrt.started_ns=12"), std::nullopt);  // unterminated
  EXPECT_EQ(parse_start_stamp("hubrt.started_ns=12x;"), std::nullopt);
  EXPECT_EQ(parse_start_stamp("hubrt.started_ns=99999999999999999999999;"), std::nullopt);
  EXPECT_EQ(parse_start_stamp("xhubrt.started_ns=12;"), std::nullopt);  // not at a pair boundary
}

TEST(TwinRules, OnlyThisHubsStateTopicsInEitherLayoutCount) {
  EXPECT_TRUE(is_own_state_topic("rt/tool_ecu/lift/state", "", "tool_ecu"));  // node-type layout
  EXPECT_TRUE(is_own_state_topic("rt/tool_ecu/state", "", "tool_ecu"));       // hub layout
  EXPECT_TRUE(is_own_state_topic("rt/station1/tool_ecu/lift/state", "/station1", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu/lift/state", "/station1", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu/command", "", "tool_ecu"));  // the planner's
  EXPECT_FALSE(is_own_state_topic("rt/lift/command", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/diagnostics", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/sim/tool_ecu/signals", "", "tool_ecu"));  // the sim bridge
  EXPECT_FALSE(is_own_state_topic("rt/sim/input", "", "tool_ecu"));             // hubctl, hubsim
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu2/lift/state", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu/lift/x/state", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu//state", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("rt/tool_ecu/lift/statex", "", "tool_ecu"));
  EXPECT_FALSE(is_own_state_topic("tool_ecu/lift/state", "", "tool_ecu"));
}

TEST(TwinRules, WritersAreGroupedByParticipant) {
  const TwinSnapshot snapshot =
      summarize_twins({writer("rt/tool_ecu/lift/state", 1, "pi-a", "41", "hubrt.started_ns=5;"),
                       writer("rt/tool_ecu/tool/state", 1, "pi-a", "41", "hubrt.started_ns=5;"),
                       writer("rt/tool_ecu/state", 2, "", "", "")});
  ASSERT_EQ(snapshot.count, 2U);
  EXPECT_EQ(snapshot.more, 0U);
  EXPECT_EQ(snapshot.peers[0].topic.view(), "/tool_ecu/lift/state");
  EXPECT_EQ(snapshot.peers[0].topics, 2U);
  EXPECT_EQ(snapshot.peers[0].host.view(), "pi-a");
  EXPECT_EQ(snapshot.peers[0].pid.view(), "41");
  EXPECT_EQ(snapshot.peers[0].started_ns, 5);
  EXPECT_EQ(snapshot.peers[1].started_ns, std::nullopt);
  runtime::TextBuffer<128> origin;
  describe_origin(snapshot.peers[0], origin);
  EXPECT_EQ(origin.view(), "host pi-a pid 41");
  describe_origin(snapshot.peers[1], origin);
  EXPECT_EQ(origin.view(), "participant 02000000:00000000:00000000");
}

TEST(TwinRules, MoreTwinsThanFitAreCounted) {
  std::vector<dds::WatchedWriter> writers;
  for (std::uint8_t p = 1; p <= 5; ++p) writers.push_back(writer("rt/dock_ecu/dock/state", p, "h", "1", ""));
  const TwinSnapshot snapshot = summarize_twins(writers);
  EXPECT_EQ(snapshot.count, TwinSnapshot::kMaxPeers);
  EXPECT_EQ(snapshot.more, 5 - TwinSnapshot::kMaxPeers);
  runtime::HubAlerts alerts;
  TwinMonitor monitor(HubStamp{1, guid(0)}, seconds(10));
  monitor.update(snapshot, Time(seconds(1)), alerts);
  EXPECT_EQ(alerts.size(), TwinSnapshot::kMaxPeers + 1);
  EXPECT_EQ(alerts.at(TwinSnapshot::kMaxPeers), "twin: and 2 more participants publish this hub's States");
}

class TwinMonitorTest : public ::testing::Test {
 protected:
  static TwinSnapshot twin_started_at(std::int64_t started_ns) {
    return summarize_twins(
        {writer("rt/dock_ecu/dock/state", 7, "pi-dock", "4242", start_stamp_user_data(started_ns))});
  }
  runtime::HubAlerts alerts_;
  const Time t0_{seconds(100)};
};

TEST_F(TwinMonitorTest, TheLaterHubReportsTheTwinAndYields) {
  TwinMonitor monitor(HubStamp{2'000, guid(1)}, seconds(10));
  monitor.update(TwinSnapshot{}, t0_, alerts_);
  EXPECT_TRUE(alerts_.empty());
  EXPECT_FALSE(monitor.must_yield());

  monitor.update(twin_started_at(1'000), t0_ + milliseconds(100), alerts_);
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_EQ(alerts_.at(0), "twin: another hub publishes /dock_ecu/dock/state from host pi-dock pid 4242");
  EXPECT_TRUE(monitor.must_yield());
  EXPECT_EQ(monitor.yielded_to().pid.view(), "4242");
}

TEST_F(TwinMonitorTest, TheEarlierHubReportsTheTwinKeepsRunningAndHoldsTheReport) {
  TwinMonitor monitor(HubStamp{1'000, guid(1)}, seconds(10));
  monitor.update(twin_started_at(2'000), t0_, alerts_);
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_EQ(alerts_.at(0), "twin: another hub publishes /dock_ecu/dock/state from host pi-dock pid 4242");
  EXPECT_FALSE(monitor.must_yield());

  // The later one left: the report stays for the hold time, then goes.
  monitor.update(TwinSnapshot{}, t0_ + milliseconds(2'500), alerts_);
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_EQ(alerts_.at(0),
            "twin: another hub published /dock_ecu/dock/state from host pi-dock pid 4242 until 2.5 s ago");
  monitor.update(TwinSnapshot{}, t0_ + seconds(10), alerts_);
  EXPECT_EQ(alerts_.size(), 1U);
  monitor.update(TwinSnapshot{}, t0_ + seconds(10) + milliseconds(1), alerts_);
  EXPECT_TRUE(alerts_.empty());
  EXPECT_FALSE(monitor.must_yield());
}

TEST_F(TwinMonitorTest, ATwinThatCameAndWentBetweenTwoCyclesIsStillReported) {
  TwinMonitor monitor(HubStamp{1'000, guid(1)}, seconds(10));
  monitor.update(TwinSnapshot{}, t0_, alerts_);
  // What the watch hands over after a twin appeared and vanished within one period.
  TwinSnapshot gone;
  gone.sightings = 1;
  gone.last = twin_started_at(2'000).peers[0];
  monitor.update(gone, t0_ + milliseconds(100), alerts_);
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_EQ(alerts_.at(0),
            "twin: another hub published /dock_ecu/dock/state from host pi-dock pid 4242 until 0.0 s ago");
  monitor.update(gone, t0_ + seconds(5), alerts_);  // the same sighting: held, not renewed
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_NE(alerts_.at(0).find("until 4.9 s ago"), std::string_view::npos) << alerts_.at(0);
  monitor.update(gone, t0_ + seconds(11), alerts_);
  EXPECT_TRUE(alerts_.empty());
}

TEST_F(TwinMonitorTest, AWriterThatIsNoHubIsReportedButNeverMakesTheHubYield) {
  TwinMonitor monitor(HubStamp{2'000, guid(1)}, seconds(10));
  monitor.update(summarize_twins({writer("rt/dock_ecu/dock/state", 7, "laptop", "99", "")}), t0_, alerts_);
  ASSERT_EQ(alerts_.size(), 1U);
  EXPECT_EQ(alerts_.at(0), "twin: another hub publishes /dock_ecu/dock/state from host laptop pid 99");
  EXPECT_FALSE(monitor.must_yield());
}

TEST_F(TwinMonitorTest, BothHubsOfATieReachOppositeVerdicts) {
  const auto twin = [](std::uint8_t participant) {
    return summarize_twins(
        {writer("rt/dock_ecu/dock/state", participant, "h", "1", start_stamp_user_data(5'000))});
  };
  TwinMonitor hub_a(HubStamp{5'000, guid(1)}, seconds(10));
  TwinMonitor hub_b(HubStamp{5'000, guid(2)}, seconds(10));
  hub_a.update(twin(2), t0_, alerts_);
  hub_b.update(twin(1), t0_, alerts_);
  EXPECT_FALSE(hub_a.must_yield());
  EXPECT_TRUE(hub_b.must_yield());
}

}  // namespace
}  // namespace hubrt::assembly
