// What `hubctl list` shows next to a bridged topic that carries nothing (docs/ros1-bridge.md).
#include "hub_diagnostics.h"

#include <gtest/gtest.h>

namespace hubrt::hubctl {
namespace {

nlohmann::ordered_json bridge_status(const std::string& message, const std::string& silent,
                                     const std::string& dropping) {
  auto values = nlohmann::ordered_json::array();
  values.push_back({{"key", "dds_topic"}, {"value", "/dock_ecu/dock/state"}});
  values.push_back({{"key", "silent"}, {"value", silent}});
  if (!dropping.empty()) values.push_back({{"key", "dropping"}, {"value", dropping}});
  return {{"level", 1},
          {"name", "hubbridge dock_ecu: /dock_ecu/dock/state"},
          {"message", message},
          {"values", values}};
}

// Issue 34: every State over a bound showed as SILENT; the drop comes first.
TEST(BridgeQuiet, DropsOverABoundComeAheadOfSilence) {
  const auto dropped =
      bridge_quiet(bridge_status("dropped 23 over a bound, forwarded none: name: 65 bytes", "true", "true"));
  ASSERT_TRUE(dropped);
  EXPECT_EQ(dropped->label, "DROPPED OVER A BOUND");
  EXPECT_EQ(dropped->message, "dropped 23 over a bound, forwarded none: name: 65 bytes");
  const auto silent = bridge_quiet(bridge_status("silent: no ROS 1 sample for 3.2 s", "true", "false"));
  ASSERT_TRUE(silent);
  EXPECT_EQ(silent->label, "SILENT");
  // An older hubbridge, without the key.
  EXPECT_EQ(bridge_quiet(bridge_status("silent: no ROS 1 sample yet", "true", ""))->label, "SILENT");
  EXPECT_FALSE(bridge_quiet(bridge_status("forwarding", "false", "false")));
  EXPECT_FALSE(bridge_quiet(nlohmann::ordered_json::parse(R"({"name": "x", "values": [{"key": 1}]})")));
  EXPECT_FALSE(bridge_quiet(nlohmann::ordered_json(3)));
}

}  // namespace
}  // namespace hubrt::hubctl
