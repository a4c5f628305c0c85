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

TEST(StationConfig, TheShippedStationHasNoMobilePlatformAndTheFullStationHasOne) {
  auto station = load_station_config(HUBRT_STATION_FILE);
  ASSERT_TRUE(station) << station.error().message;
  EXPECT_FALSE(station->mobile_platform) << "the three-hub station has no mir_com: the kit must stay";
  auto full = load_station_config(HUBRT_FULL_STATION_FILE);
  ASSERT_TRUE(full) << full.error().message;
  ASSERT_TRUE(full->mobile_platform);
  EXPECT_EQ(full->mobile_platform->state_topic, "/mir_com/mover/state");
  EXPECT_EQ(full->mobile_platform->field, "");
  EXPECT_EQ(full->mobile_platform->at_station, "station");
  EXPECT_EQ(full->mobile_platform->kit, "kit");
  // The same world otherwise.
  EXPECT_EQ(full->hubs, station->hubs);
  EXPECT_EQ(full->places, station->places);
  EXPECT_EQ(full->robot_travel, station->robot_travel);
  ASSERT_EQ(full->tools.size(), station->tools.size());
  for (std::size_t i = 0; i < full->tools.size(); ++i) {
    EXPECT_EQ(full->tools[i].name, station->tools[i].name);
    EXPECT_EQ(full->tools[i].tool_id_signal, station->tools[i].tool_id_signal);
    EXPECT_EQ(full->tools[i].dock_signal, station->tools[i].dock_signal);
  }
  EXPECT_EQ(full->frame_rests, station->frame_rests);
  EXPECT_EQ(full->arm_home_signal, station->arm_home_signal);
  EXPECT_EQ(full->home_above_mm, station->home_above_mm);
}

TEST(StationConfig, TheMobilePlatformSection) {
  auto node_type =
      parse(std::string("mobile_platform: {state: /mir_com/mover/state, at_station: station}\n") + kTools);
  ASSERT_TRUE(node_type) << node_type.error().message;
  ASSERT_TRUE(node_type->mobile_platform);
  EXPECT_EQ(node_type->mobile_platform->state_topic, "/mir_com/mover/state");
  EXPECT_EQ(node_type->mobile_platform->field, "");
  EXPECT_EQ(node_type->mobile_platform->at_station, "station");
  EXPECT_EQ(node_type->mobile_platform->kit, "kit");
  EXPECT_EQ(node_type->mobile_platform->timeout, std::chrono::milliseconds(1000));

  auto hub =
      parse(std::string("mobile_platform:\n  state: /mir_com/state\n  field: mover\n  at_station: dock 2\n"
                        "  timeout_ms: 2500\n") +
            kTools);
  ASSERT_TRUE(hub) << hub.error().message;
  ASSERT_TRUE(hub->mobile_platform);
  EXPECT_EQ(hub->mobile_platform->state_topic, "/mir_com/state");
  EXPECT_EQ(hub->mobile_platform->field, "mover");
  EXPECT_EQ(hub->mobile_platform->at_station, "dock 2") << "a MiR position is any name";
  EXPECT_EQ(hub->mobile_platform->timeout, std::chrono::milliseconds(2500));

  auto none = parse(kTools);
  ASSERT_TRUE(none) << none.error().message;
  EXPECT_FALSE(none->mobile_platform);
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
      {"mobile_platform: {state: /m/state, at_station: s, colour: red}\n" + std::string(kTools),
       "station.yaml:1"},
      {"mobile_platform: {state: /m/state, at_station: s, colour: red}\n" + std::string(kTools),
       "unknown key"},
      {"mobile_platform: {at_station: s}\n" + std::string(kTools), "missing required key 'state'"},
      {"mobile_platform: {state: mir/state, at_station: s}\n" + std::string(kTools), "mir/state"},
      {"mobile_platform: {state: '', at_station: s}\n" + std::string(kTools), "state"},
      {"mobile_platform: {state: /m/state}\n" + std::string(kTools), "missing required key 'at_station'"},
      {"mobile_platform: {state: /m/state, at_station: ''}\n" + std::string(kTools), "must not be empty"},
      {"mobile_platform: {state: /m/state, at_station: " + std::string(65, 'x') + "}\n" + kTools,
       "at most 64 bytes"},
      {"mobile_platform: {state: /m/state, at_station: s, field: 'mover.x'}\n" + std::string(kTools),
       "'mover.x' is not a name"},
      {"mobile_platform: {state: /m/state, at_station: s, field: ''}\n" + std::string(kTools),
       "must not be empty"},
      {"mobile_platform: {state: /m/state, at_station: s, field: poses}\n" + std::string(kTools),
       "MirComState has no RobotMoverState field 'poses'"},
      {"mobile_platform: {state: /m/state, at_station: s, kit: roof}\n" + std::string(kTools),
       "'roof' is not one of the robot's places"},
      {"ladder_frame: {rests: [engine], start: engine}\nmobile_platform: {state: /m/state, at_station: s}\n" +
           std::string(kTools),
       "the ladder frame cannot lie at 'kit'"},
      {"ladder_frame: {rests: [kit, engine, home]}\nmobile_platform: {state: /m/state, at_station: s, kit: "
       "home}\n" +
           std::string(kTools),
       "the robot starts at 'home'"},
      {"mobile_platform: {state: /m/state, at_station: s, timeout_ms: 0}\n" + std::string(kTools),
       "timeout_ms"},
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
