// What a bridge's /diagnostics status says first: drops over a bound ahead of silence (issue 34:
// a node whose every State was over a bound showed as "silent"), and a publisher the ROS master
// does not list. Also the bounded list of publishers heard.
#include "bridge_diagnostics.h"

#include <gtest/gtest.h>

namespace hubrt::hubbridge {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

BridgeFile dock_file() {
  BridgeFile file;
  file.name = "dock_ecu";
  file.silent_after_s = 1.0;
  return file;
}

std::vector<std::unique_ptr<Bridge>> one_state_bridge() {
  std::vector<std::unique_ptr<Bridge>> bridges;
  bridges.push_back(std::make_unique<Bridge>());
  Bridge& b = *bridges.back();
  b.config = {"/dock_ecu/dock/state", "/dock_ecu/dock/state", "hub_msgs/DockState", Direction::kRos1ToDds};
  b.type.ros1_name = "hub_msgs/DockState";
  return bridges;
}

struct Status {
  int level = -1;
  std::string message;
  std::map<std::string, std::string> values;
};

Status status_of(const nlohmann::ordered_json& array) {
  Status out;
  const auto& s = array.at("status").at(0);
  out.level = s.at("level").get<int>();
  out.message = s.at("message").get<std::string>();
  for (const auto& kv : s.at("values"))
    out.values[kv.at("key").get<std::string>()] = kv.at("value").get<std::string>();
  return out;
}

TEST(BridgeDiagnostics, DropsOverABoundComeAheadOfSilence) {
  auto bridges = one_state_bridge();
  Bridge& b = *bridges[0];
  const std::int64_t now = 100 * kSecond;
  b.counters.dropped = 23;
  b.counters.last_drop_ns = now - kSecond / 2;
  b.last_problem = "dropped a message from /other: name: 65 bytes, over the bound of 64 (dropped, not cut)";
  const Status s = status_of(bridge_diagnostics(dock_file(), bridges, {}, 1, now, 0));
  EXPECT_EQ(s.level, 1);
  EXPECT_EQ(
      s.message,
      "dropped 23 over a bound, forwarded none: dropped a message from /other: name: 65 bytes, over the "
      "bound of 64 (dropped, not cut)");
  EXPECT_EQ(s.values.at("dropping"), "true");
  EXPECT_EQ(s.values.at("silent"), "true") << "nothing reaches DDS all the same";

  // Some States forwarded, the last 3 s ago, drops going on: still the drops first.
  b.counters.last_forward_ns = now - 3 * kSecond;
  EXPECT_EQ(status_of(bridge_diagnostics(dock_file(), bridges, {}, 1, now, 0))
                .message.rfind("dropped 23 over a bound, forwarded none for 3.0 s: ", 0),
            0U);
  // The drops stopped longer ago than the silence window: plain silence again.
  b.counters.last_drop_ns = now - 2 * kSecond;
  const Status quiet = status_of(bridge_diagnostics(dock_file(), bridges, {}, 1, now, 0));
  EXPECT_EQ(quiet.message, "silent: no ROS 1 sample for 3.0 s");
  EXPECT_EQ(quiet.values.at("dropping"), "false");
}

TEST(BridgeDiagnostics, ReportsAPublisherTheMasterDoesNotList) {
  auto bridges = one_state_bridge();
  const std::int64_t now = 100 * kSecond;
  bridges[0]->counters.last_forward_ns = now - kSecond / 10;
  std::vector<EndpointSync> sync(1);
  sync[0].unregistered = {"/dock_ecu_ros1_42"};
  Status s = status_of(bridge_diagnostics(dock_file(), bridges, sync, 2, now, 0));
  EXPECT_EQ(s.level, 1);
  EXPECT_EQ(s.message.rfind("publisher /dock_ecu_ros1_42 is not registered with the ROS master", 0), 0U)
      << s.message;
  EXPECT_EQ(s.values.at("unregistered_publishers"), "/dock_ecu_ros1_42");
  sync[0] = {{}, {"/dock_ecu_ros1_42"}};
  s = status_of(bridge_diagnostics(dock_file(), bridges, sync, 2, now, 0));
  EXPECT_EQ(s.level, 0);
  EXPECT_EQ(s.values.at("registered_for"), "/dock_ecu_ros1_42");
  EXPECT_EQ(s.values.at("ros1_registrations"), "2");
}

TEST(HeardPublishers, KeepsTheLatestAndForgetsTheOldestBeyondItsBound) {
  HeardPublishers heard;
  heard.heard("/a", 10);
  heard.heard("/b", 20);
  heard.heard("/a", 30);
  EXPECT_EQ(heard.since(25), std::vector<std::string>{"/a"});
  EXPECT_EQ(heard.since(0), (std::vector<std::string>{"/a", "/b"}));
  for (std::size_t i = 0; i < HeardPublishers::kMax; ++i)
    heard.heard("/n" + std::to_string(i), 100 + static_cast<std::int64_t>(i));
  const auto all = heard.since(0);
  EXPECT_EQ(all.size(), HeardPublishers::kMax);
  EXPECT_EQ(std::count(all.begin(), all.end(), "/b"), 0) << "the one heard longest ago goes first";
  EXPECT_EQ(std::count(all.begin(), all.end(), "/a"), 0);
}

}  // namespace
}  // namespace hubrt::hubbridge
