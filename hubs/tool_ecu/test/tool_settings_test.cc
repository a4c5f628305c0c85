#include "tool_settings.h"

#include <gtest/gtest.h>

#include "hubrt/hal/board/board_loader.h"

namespace hubrt::tool_ecu {
namespace {

using std::chrono::milliseconds;

config::HubConfig shipped_config() {
  auto config = config::load_hub_config(std::string(HUBRT_HUBS_DIR) + "/tool_ecu/tool_ecu.yaml");
  EXPECT_TRUE(config) << config.error().message;
  return *config;
}

const config::NodeConfig& node_named(const config::HubConfig& config, std::string_view name) {
  for (const auto& node : config.nodes) {
    if (node.name == name) return node;
  }
  throw std::runtime_error("no such node");
}

TEST(ToolSettings, TheShippedConfigurationIsWhatTheReadmeDescribes) {
  const auto config = shipped_config();
  auto tool = parse_smart_tool_settings(node_named(config, "tool"));
  ASSERT_TRUE(tool) << tool.error().message;
  EXPECT_EQ(tool->bus, "tool_bus");
  EXPECT_EQ(tool->node_id, 1);
  EXPECT_EQ(tool->robot_state, "rsp");
  ASSERT_EQ(tool->programs.size(), 2u);
  EXPECT_EQ(tool->programs[0].name, "ladder_frame_bolt");
  // 10.0 Nm, 150.0°..200.0° in the protocol's units (0.01 Nm, 0.1°).
  EXPECT_EQ(tool->programs[0].program, (protocol::smart_tool::Program{12, 1000, 1500, 2000}));
  EXPECT_EQ(tool->manual_program, 1);
  EXPECT_EQ(tool->start_timeout, milliseconds(500));

  auto lift = parse_lift_settings(node_named(config, "lift"));
  ASSERT_TRUE(lift) << lift.error().message;
  ASSERT_EQ(lift->positions.size(), 3u);
  EXPECT_EQ(lift->positions[0].name, "home");
  EXPECT_EQ(lift->positions[0].tenth_mm, 3800);
  EXPECT_EQ(lift->positions[1].name, "float");
  EXPECT_EQ(lift->positions[2].tenth_mm, 1200);
  EXPECT_EQ(lift->answer_within, milliseconds(500));

  // The host simulation board provides everything the shipped nodes use.
  auto board = hal::load_board(std::string(HUBRT_BOARDS_DIR) + "/host-sim.yaml");
  ASSERT_TRUE(board) << board.error().message;
  hal::BoardRequirements required;
  required.hub = "tool_ecu";
  add_requirements(*tool, required);
  add_requirements(*lift, required);
  EXPECT_EQ(required.inputs.size(), 7u);
  EXPECT_EQ(required.outputs.size(), 2u);
  EXPECT_TRUE(hal::check_requirements(*board, required));
}

std::string tool_error(const std::string& node_yaml) {
  auto root = config::YamlMap::load_string("hub: tool_ecu\nnodes:\n  tool:\n" + node_yaml, "tool.yaml");
  EXPECT_TRUE(root) << root.error().message;
  auto config = config::parse_hub_config(*root);
  EXPECT_TRUE(config) << config.error().message;
  auto settings = parse_smart_tool_settings(config->nodes.at(0));
  return settings ? "no error" : settings.error().message;
}

std::string lift_error(const std::string& node_yaml) {
  auto root = config::YamlMap::load_string("hub: tool_ecu\nnodes:\n  lift:\n" + node_yaml, "tool.yaml");
  EXPECT_TRUE(root) << root.error().message;
  auto config = config::parse_hub_config(*root);
  EXPECT_TRUE(config) << config.error().message;
  auto settings = parse_lift_settings(config->nodes.at(0));
  return settings ? "no error" : settings.error().message;
}

constexpr char kProgram[] =
    "    programs:\n      p: {number: 3, torque_nm: 5, angle_min_deg: 10, angle_max_deg: 90}\n";

TEST(ToolSettings, BadSmartToolSettingsNameTheLine) {
  EXPECT_EQ(tool_error(std::string("    type: smart_tool\n") + kProgram), "no error");
  EXPECT_EQ(tool_error("    type: smart_tool\n    programs: {}\n"),
            "tool.yaml:5:15: nodes.tool.programs: a smart tool has 1 to 32 programs, got 0");
  EXPECT_EQ(tool_error("    type: smart_tool\n    programs:\n"
                       "      a: {number: 3, torque_nm: 5, angle_min_deg: 10, angle_max_deg: 90}\n"
                       "      b: {number: 3, torque_nm: 6, angle_min_deg: 10, angle_max_deg: 90}\n"),
            "tool.yaml:7:19: nodes.tool.programs.b.number: program number 3 is used twice");
  EXPECT_EQ(
      tool_error("    type: smart_tool\n    programs:\n"
                 "      a: {number: 3, torque_nm: 5, angle_min_deg: 90, angle_max_deg: 10}\n"),
      "tool.yaml:6:70: nodes.tool.programs.a.angle_max_deg: the angle window's maximum is below its minimum");
  EXPECT_EQ(tool_error("    type: smart_tool\n    programs:\n"
                       "      a: {number: 3, torque_nm: 700, angle_min_deg: 10, angle_max_deg: 90}\n"),
            "tool.yaml:6:33: nodes.tool.programs.a.torque_nm: 700 is out of range [0.01, 655.35]");
  EXPECT_EQ(tool_error("    type: smart_tool\n    programs:\n"
                       "      unknown: {number: 3, torque_nm: 5, angle_min_deg: 10, angle_max_deg: 90}\n"),
            "tool.yaml:6:25: nodes.tool.programs.unknown.number: 'unknown' is reserved: the State says "
            "selected_program 'unknown' when the controller's status is not current");
  EXPECT_EQ(tool_error(std::string("    type: smart_tool\n    manual_program: q\n") + kProgram),
            "tool.yaml:5:21: nodes.tool.manual_program: 'q' is not one of the programs");
  EXPECT_EQ(tool_error(std::string("    type: smart_tool\n    node_id: 128\n") + kProgram),
            "tool.yaml:5:14: nodes.tool.node_id: 128 is out of range [1, 127]");
  EXPECT_EQ(
      tool_error(std::string("    type: smart_tool\n    signals: {run_fwd: x}\n") + kProgram),
      "tool.yaml:5:15: nodes.tool.signals.run_fwd: unknown key (expected one of: run_forward, run_reverse, "
      "button_forward, button_reverse, torque_reached, summary_alarm, arm_home, arm_pre_home, "
      "arm_out_of_range)");
}

TEST(ToolSettings, BadLiftSettingsNameTheLine) {
  EXPECT_EQ(lift_error("    type: lift\n    positions: {home: 10}\n"), "no error");
  EXPECT_EQ(lift_error("    type: lift\n    positions: {}\n"),
            "tool.yaml:5:16: nodes.lift.positions: a lift has 1 to 16 named positions, got 0");
  EXPECT_EQ(lift_error("    type: lift\n    positions: {home: -1}\n"),
            "tool.yaml:5:23: nodes.lift.positions.home: -1 is out of range [0, 6553.5]");
  EXPECT_EQ(
      lift_error("    type: lift\n    positions: {9up: 1}\n"),
      "tool.yaml:5:22: nodes.lift.positions.9up: '9up' is not a usable position name: use letters, digits "
      "and underscores, starting with a letter");
  EXPECT_EQ(lift_error("    type: lift\n    positions: {home: 1}\n    drive_watchdog_ms: 70000\n"),
            "tool.yaml:6:24: nodes.lift.drive_watchdog_ms: 70000 is out of range [0, 60000]");
}

}  // namespace
}  // namespace hubrt::tool_ecu
