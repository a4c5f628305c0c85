// The station description: the shipped one loads, and mistakes are refused with file:line and
// what is wrong.
#include "hubrt/sim/station/station_config.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

namespace hubrt::sim::station {
namespace {

using ::testing::HasSubstr;

Expected<StationConfig> parse(const std::string& text) {
  auto root = config::YamlMap::load_string(text, "station.yaml");
  if (!root) return std::move(root).error();
  return parse_station_config(*root);
}

constexpr const char* kTools = R"(tools:
  ladder_frame_tool: {tool_id: rsp.tool_id.ladder_frame_tool, dock: dock.slot.ladder_frame_tool}
  smart_tool: {tool_id: rsp.tool_id.smart_tool, dock: dock.slot.smart_tool}
)";

TEST(StationConfig, TheShippedStationLoads) {
  auto config = load_station_config(HUBRT_STATION_FILE);
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->hubs[static_cast<std::size_t>(HubRole::kRsp)], "rsp_ecu");
  ASSERT_EQ(config->tools.size(), 3u);
  EXPECT_EQ(config->tools[1].name, "smart_tool");
  EXPECT_EQ(config->tools[1].dock_signal, "dock.slot.smart_tool");
  EXPECT_TRUE(config->is_location("engine"));
  EXPECT_TRUE(config->is_location("filter_tool"));
  EXPECT_FALSE(config->is_location("canteen"));
}

TEST(StationConfig, HubNamesCanBeChanged) {
  auto config = parse(std::string("hubs: {rsp_ecu: rsp2}\n") + kTools);
  ASSERT_TRUE(config) << config.error().message;
  EXPECT_EQ(config->hubs[static_cast<std::size_t>(HubRole::kRsp)], "rsp2");
  EXPECT_EQ(config->hubs[static_cast<std::size_t>(HubRole::kTool)], "tool_ecu");
}

TEST(StationConfig, MistakesNameFileLineAndWhatIsWrong) {
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {std::string("hubs: {lift_ecu: x}\n") + kTools, "station.yaml:1"},
      {std::string("robot: {start: canteen}\n") + kTools, "the robot cannot start at 'canteen'"},
      {std::string("robot: {places: [home, smart_tool]}\n") + kTools,
       "'smart_tool' is a robot place as well as an end-effector"},
      {std::string("ladder_frame: {tool: gripper_tool}\n") + kTools,
       "'gripper_tool' is not one of the tools"},
      {std::string("ladder_frame: {start: roof}\n") + kTools,
       "'roof' is not a place where the frame can lie"},
      {std::string("smart_tool_arm: {home_above_mm: 300, pre_home_above_mm: 330}\n") + kTools,
       "must be below home_above_mm"},
      {std::string("smart_tool_arm: {operating_at: roof}\n") + kTools,
       "'roof' is not one of the robot's places"},
      {"tools:\n  a_tool: {tool_id: x, dock: y, start: robot}\n  b_tool: {tool_id: x, dock: y, start: "
       "robot}\n",
       "only one end-effector can start on the robot"},
      {"tools:\n  smart_tool: {dock: y}\n", "tool_id"},
      {"rate_hz: 0\n" + std::string(kTools), "rate_hz"},
  };
  for (const auto& c : cases) {
    auto config = parse(c.text);
    ASSERT_FALSE(config) << c.text;
    EXPECT_THAT(config.error().message, HasSubstr(c.expected)) << c.text;
    EXPECT_THAT(config.error().message, HasSubstr("station.yaml:")) << c.text;
  }
}

}  // namespace
}  // namespace hubrt::sim::station
