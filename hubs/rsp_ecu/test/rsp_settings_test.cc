// The tool-changer node's settings and the hub type's requirements: the shipped configuration
// fits the simulation board; every bad setting is an error that names file and line.
#include "rsp_settings.h"

#include <gtest/gtest.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_loader.h"

#include "rsp_ecu_hub_type.h"

namespace hubrt::rsp_ecu {
namespace {

const std::string kNode = R"(    type: tool_changer
    lock_valve: rsp.lock_valve
    gripper_valve: rsp.gripper_valve
    tool_id: {ladder_frame_tool: rsp.tool_id.ladder_frame_tool, smart_tool: rsp.tool_id.smart_tool}
    gripper_confirm: [rsp.gripper.confirm_a, rsp.gripper.confirm_b]
    pressure_switch: rsp.pressure_ok
)";

Expected<config::HubConfig> hub_text(const std::string& node_yaml, bool with_subscription = true) {
  std::string text = "hub: rsp_ecu\n";
  if (with_subscription)
    text += "subscriptions:\n  dock: {topic: /dock_ecu/dock/state, type: hub_msgs/msg/DockState}\n";
  text += "nodes:\n  rsp:\n" + node_yaml;
  auto root = config::YamlMap::load_string(text, "rsp.yaml");
  if (!root) return std::move(root).error();
  return config::parse_hub_config(*root);
}

Expected<RspSettings> parse_text(const std::string& node_yaml) {
  auto config = hub_text(node_yaml);
  if (!config) return std::move(config).error();
  return parse_rsp_settings(config->nodes.at(0));
}

std::string error_of(const std::string& node_yaml) {
  auto parsed = parse_text(node_yaml);
  return parsed ? std::string("(no error)") : parsed.error().message;
}

TEST(RspSettingsTest, TheShippedConfigurationFitsTheSimulationBoard) {
  auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/rsp_ecu/rsp_ecu.yaml");
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->name, "rsp_ecu");
  EXPECT_EQ(config->layout, config::Layout::kNodeType);
  ASSERT_EQ(config->nodes.size(), 1u);
  EXPECT_EQ(config->nodes[0].name, "rsp");
  ASSERT_EQ(config->subscriptions.size(), 1u);
  EXPECT_EQ(config->subscriptions[0].topic, "/dock_ecu/dock/state");
  EXPECT_EQ(config->subscriptions[0].type, "hub_msgs/msg/DockState");

  auto settings = parse_rsp_settings(config->nodes[0]);
  ASSERT_TRUE(settings) << settings.error().message;
  ASSERT_EQ(settings->tool_lines.size(), 3u);
  EXPECT_EQ(settings->tool_lines[0].tool, "ladder_frame_tool");
  EXPECT_EQ(settings->tool_lines[2].signal, "rsp.tool_id.filter_tool");
  EXPECT_EQ(settings->gripper_tool, "ladder_frame_tool");
  EXPECT_EQ(settings->lock_actuation, std::chrono::milliseconds(200));
  EXPECT_EQ(settings->gripper_confirm, std::chrono::milliseconds(500));

  auto required = rsp_ecu_hub_type().requirements(*config);
  ASSERT_TRUE(required) << required.error().message;
  EXPECT_EQ(required->outputs, (std::vector<std::string>{"rsp.lock_valve", "rsp.gripper_valve"}));
  EXPECT_EQ(required->inputs.size(), 6u);
  auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
  ASSERT_TRUE(board) << board.error().message;
  EXPECT_TRUE(hal::check_requirements(*board, *required));
  auto pi = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/rpi4-rsp-ecu.yaml");
  ASSERT_TRUE(pi) << pi.error().message;
  auto on_pi = hal::check_requirements(*pi, *required);
  EXPECT_TRUE(on_pi) << on_pi.error().message;
}

TEST(RspSettingsTest, DefaultsApplyWhenTimingIsNotGiven) {
  auto parsed = parse_text(kNode);
  ASSERT_TRUE(parsed) << parsed.error().message;
  EXPECT_EQ(parsed->dock_subscription, "dock");
  EXPECT_EQ(parsed->lock_actuation, std::chrono::milliseconds(200));
}

TEST(RspSettingsTest, BadSettingsNameFileLineAndProblem) {
  EXPECT_NE(error_of(kNode + "    lock_delay_ms: 5\n").find("rsp.yaml:"), std::string::npos);
  EXPECT_NE(error_of(kNode + "    lock_delay_ms: 5\n").find("lock_delay_ms"), std::string::npos);

  const std::string reserved = error_of(R"(    type: tool_changer
    lock_valve: rsp.lock_valve
    gripper_valve: rsp.gripper_valve
    tool_id: {none: rsp.tool_id.ladder_frame_tool}
    gripper_confirm: [rsp.gripper.confirm_a, rsp.gripper.confirm_b]
    pressure_switch: rsp.pressure_ok
)");
  EXPECT_NE(reserved.find("'none' is reserved, not a tool name"), std::string::npos) << reserved;
  EXPECT_NE(reserved.find("rsp.yaml:9:"), std::string::npos) << reserved;

  const std::string one_confirm = error_of(R"(    type: tool_changer
    lock_valve: rsp.lock_valve
    gripper_valve: rsp.gripper_valve
    tool_id: {ladder_frame_tool: rsp.tool_id.ladder_frame_tool}
    gripper_confirm: [rsp.gripper.confirm_a]
    pressure_switch: rsp.pressure_ok
)");
  EXPECT_NE(one_confirm.find("expected the two confirm inputs [A, B], got 1 entries"), std::string::npos)
      << one_confirm;

  const std::string gripper_tool = error_of(kNode + "    gripper_tool: filter_tool\n");
  EXPECT_NE(gripper_tool.find("'filter_tool' is not one of the tools under tool_id"), std::string::npos)
      << gripper_tool;

  const std::string twice = error_of(R"(    type: tool_changer
    lock_valve: rsp.lock_valve
    gripper_valve: rsp.gripper_valve
    tool_id: {ladder_frame_tool: rsp.tool_id.ladder_frame_tool, smart_tool: rsp.pressure_ok}
    gripper_confirm: [rsp.gripper.confirm_a, rsp.gripper.confirm_b]
    pressure_switch: rsp.pressure_ok
)");
  EXPECT_NE(twice.find("signal 'rsp.pressure_ok' is used twice by this node"), std::string::npos) << twice;

  const std::string slow = error_of(kNode + "    gripper_confirm_ms: 0\n");
  EXPECT_NE(slow.find("gripper_confirm_ms"), std::string::npos) << slow;

  const std::string missing = error_of("    type: tool_changer\n    lock_valve: rsp.lock_valve\n");
  EXPECT_NE(missing.find("gripper_valve"), std::string::npos) << missing;
}

TEST(RspSettingsTest, TheHubTypeRefusesAConfigurationWithoutTheDockSubscription) {
  auto config = hub_text(kNode, false);
  ASSERT_TRUE(config) << config.error().message;
  auto required = rsp_ecu_hub_type().requirements(*config);
  ASSERT_FALSE(required);
  EXPECT_NE(required.error().message.find("needs the Dock ECU State as subscription 'dock'"),
            std::string::npos)
      << required.error().message;
}

TEST(RspSettingsTest, TheHubTypeRefusesNodesOfAnotherType) {
  auto config = hub_text("    type: dock\n");
  ASSERT_TRUE(config) << config.error().message;
  auto required = rsp_ecu_hub_type().requirements(*config);
  ASSERT_FALSE(required);
  EXPECT_NE(required.error().message.find("an rsp_ecu hub has nodes of type 'tool_changer' only, not 'dock'"),
            std::string::npos)
      << required.error().message;
}

}  // namespace
}  // namespace hubrt::rsp_ecu
