#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"

#include "tool_ecu_hub_type.h"

namespace hubrt::tool_ecu {
namespace {

Expected<hal::BoardRequirements> requirements_of(const std::string& yaml) {
  auto root = config::YamlMap::load_string(yaml, "tool.yaml");
  EXPECT_TRUE(root) << root.error().message;
  auto config = config::parse_hub_config(*root);
  EXPECT_TRUE(config) << config.error().message;
  return tool_ecu_hub_type().requirements(*config);
}

constexpr char kTool[] =
    "  tool:\n    type: smart_tool\n    programs: {p: {number: 1, torque_nm: 5, angle_min_deg: 0, "
    "angle_max_deg: 90}}\n";
constexpr char kRsp[] =
    "subscriptions:\n  rsp: {topic: /rsp_ecu/rsp/state, type: hub_msgs/msg/RspState, timeout_ms: 500}\n";

TEST(ToolEcuHubType, NeedsTheRspSubscriptionForTheSmartToolInterlock) {
  EXPECT_EQ(tool_ecu_hub_type().name(), "tool_ecu");
  auto ok = requirements_of(std::string("hub: tool_ecu\n") + kRsp + "nodes:\n" + kTool);
  ASSERT_TRUE(ok) << ok.error().message;
  EXPECT_EQ(ok->can_buses, std::vector<std::string>{"tool_bus"});

  auto missing = requirements_of(std::string("hub: tool_ecu\nnodes:\n") + kTool);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message,
            "tool.yaml:4:5: nodes.tool: node 'tool' needs the RSP ECU State as subscription 'rsp', and "
            "tool.yaml has "
            "no such subscription (add subscriptions: {rsp: {topic: /rsp_ecu/rsp/state, type: "
            "hub_msgs/msg/RspState, timeout_ms: 500}})");
}

TEST(ToolEcuHubType, TheOperatorInterlockNeedsItsSubscriptionAndItsType) {
  const std::string tool = std::string(kTool) + "    operator_state: operator\n";
  auto missing = requirements_of(std::string("hub: tool_ecu\n") + kRsp + "nodes:\n" + tool);
  ASSERT_FALSE(missing);
  EXPECT_EQ(missing.error().message.rfind("tool.yaml:8:21: nodes.tool.operator_state: node 'tool' takes the "
                                          "operator hub's State from subscription 'operator', and tool.yaml "
                                          "has no such subscription",
                                          0),
            0U)
      << missing.error().message;

  const std::string with_operator =
      std::string("hub: tool_ecu\n") + kRsp +
      "  operator: {topic: /operator_hub/panel/state, type: hub_msgs/msg/OperatorPanelState, timeout_ms: "
      "500}\nnodes:\n" +
      tool;
  ASSERT_TRUE(requirements_of(with_operator));
  auto root = config::YamlMap::load_string(with_operator, "tool.yaml");
  ASSERT_TRUE(root);
  auto config = config::parse_hub_config(*root);
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_TRUE(tool_ecu_hub_type().check(*config));

  // A subscription of another type cannot feed it: said before anything opens.
  std::string wrong_type = with_operator;
  wrong_type.replace(wrong_type.find("OperatorPanelState"), 18, "DockState");
  auto wrong_root = config::YamlMap::load_string(wrong_type, "tool.yaml");
  ASSERT_TRUE(wrong_root);
  auto wrong = config::parse_hub_config(*wrong_root);
  ASSERT_TRUE(wrong) << wrong.error().message;
  auto refused = tool_ecu_hub_type().check(*wrong);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("operator"), std::string::npos) << refused.error().message;
}

TEST(ToolEcuHubType, KnowsItsNodeTypesOnly) {
  auto wrong = requirements_of("hub: tool_ecu\nnodes:\n  dock:\n    type: dock\n");
  ASSERT_FALSE(wrong);
  EXPECT_EQ(
      wrong.error().message,
      "tool.yaml:4:11: nodes.dock.type: a tool_ecu hub has nodes of type 'smart_tool' or 'lift', not 'dock'");
  auto lift = requirements_of("hub: tool_ecu\nnodes:\n  lift:\n    type: lift\n    positions: {home: 1}\n");
  ASSERT_TRUE(lift) << lift.error().message;
  EXPECT_EQ(lift->modbus_devices, std::vector<std::string>{"lift_drive"});
}

}  // namespace
}  // namespace hubrt::tool_ecu
