#include "hubrt/sim/station/station_config.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <fmt/format.h>
#include <fmt/ranges.h>

#include "hubrt/config/hub_config.h"
#include "hubrt/dds/ros_names.h"

namespace hubrt::sim::station {
namespace {

using config::YamlMap;

bool contains(const std::vector<std::string>& list, std::string_view item) {
  return std::find(list.begin(), list.end(), item) != list.end();
}

Expected<std::string> identifier(const YamlMap& map, std::string_view key, std::string fallback) {
  auto value = map.string_or(key, std::move(fallback));
  if (value && !config::is_ros_name_token(*value)) {
    return map.error_at(key, fmt::format("'{}' is not a name: use letters, digits and underscores, starting "
                                         "with a letter",
                                         *value));
  }
  return value;
}

Expected<void> hubs(const YamlMap& root, StationConfig& out) {
  if (!root.has("hubs")) return {};
  auto map = root.map("hubs");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"tool_ecu", "rsp_ecu", "dock_ecu"}); !ok) return ok;
  for (std::size_t role = 0; role < kHubRoles; ++role) {
    const auto key = to_string(static_cast<HubRole>(role));
    auto name = identifier(*map, key, out.hubs[role]);
    if (!name) return std::move(name).error();
    out.hubs[role] = *name;
  }
  return {};
}

Expected<void> robot(const YamlMap& root, StationConfig& out) {
  if (!root.has("robot")) return {};
  auto map = root.map("robot");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"places", "start", "travel_ms"}); !ok) return ok;
  if (map->has("places")) {
    auto places = map->list_of_strings("places");
    if (!places) return std::move(places).error();
    if (places->empty()) return map->error_at("places", "the robot needs at least one place to be");
    for (const auto& place : *places) {
      if (!config::is_ros_name_token(place)) {
        return map->error_at("places", fmt::format("'{}' is not a name", place));
      }
    }
    out.places = std::move(*places);
  }
  auto start = identifier(*map, "start", out.robot_start);
  if (!start) return std::move(start).error();
  out.robot_start = *start;
  auto travel = map->integer_or("travel_ms", 300, 0, 600'000);
  if (!travel) return std::move(travel).error();
  out.robot_travel = std::chrono::milliseconds(*travel);
  return {};
}

Expected<void> changer(const YamlMap& root, StationConfig& out) {
  if (!root.has("changer")) return {};
  auto map = root.map("changer");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"lock_valve", "gripper_valve"}); !ok) return ok;
  auto lock = map->string_or("lock_valve", out.lock_valve);
  if (!lock) return std::move(lock).error();
  auto gripper = map->string_or("gripper_valve", out.gripper_valve);
  if (!gripper) return std::move(gripper).error();
  out.lock_valve = *lock;
  out.gripper_valve = *gripper;
  return {};
}

Expected<void> tools(const YamlMap& root, StationConfig& out) {
  auto entries = root.named_maps("tools");
  if (!entries) return std::move(entries).error();
  if (entries->empty()) return root.error_at("tools", "a station needs at least one end-effector");
  int on_robot = 0;
  for (auto& [name, map] : *entries) {
    if (auto ok = map.only_keys({"tool_id", "dock", "start"}); !ok) return ok;
    if (!config::is_ros_name_token(name)) return map.error(fmt::format("'{}' is not a name", name));
    if (contains(out.places, name)) {
      return map.error(
          fmt::format("'{}' is a robot place as well as an end-effector: the robot could not tell "
                      "the dock slot from the place",
                      name));
    }
    ToolConfig tool;
    tool.name = name;
    auto tool_id = map.string("tool_id");
    if (!tool_id) return std::move(tool_id).error();
    auto dock = map.string("dock");
    if (!dock) return std::move(dock).error();
    auto start = map.choice_or("start", "dock", {"dock", "robot"});
    if (!start) return std::move(start).error();
    tool.tool_id_signal = *tool_id;
    tool.dock_signal = *dock;
    tool.starts_on_robot = *start == "robot";
    if (tool.starts_on_robot && ++on_robot > 1) {
      return map.error_at("start", "only one end-effector can start on the robot");
    }
    out.tools.push_back(std::move(tool));
  }
  return {};
}

Expected<void> ladder_frame(const YamlMap& root, StationConfig& out) {
  if (!root.has("ladder_frame")) return {};
  auto map = root.map("ladder_frame");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"tool", "start", "rests"}); !ok) return ok;
  auto tool = map->string_or("tool", out.frame_tool);
  if (!tool) return std::move(tool).error();
  if (out.find_tool(*tool) == nullptr) {
    return map->error_at("tool", fmt::format("'{}' is not one of the tools", *tool));
  }
  if (map->has("rests")) {
    auto rests = map->list_of_strings("rests");
    if (!rests) return std::move(rests).error();
    for (const auto& rest : *rests) {
      if (!contains(out.places, rest)) {
        return map->error_at("rests", fmt::format("'{}' is not one of the robot's places ({})", rest,
                                                  fmt::join(out.places, ", ")));
      }
    }
    out.frame_rests = std::move(*rests);
  }
  auto start = map->string_or("start", out.frame_start);
  if (!start) return std::move(start).error();
  if (!contains(out.frame_rests, *start)) {
    return map->error_at("start", fmt::format("'{}' is not a place where the frame can lie ({})", *start,
                                              fmt::join(out.frame_rests, ", ")));
  }
  out.frame_tool = *tool;
  out.frame_start = *start;
  return {};
}

Expected<void> smart_tool_arm(const YamlMap& root, StationConfig& out) {
  if (!root.has("smart_tool_arm")) return {};
  auto map = root.map("smart_tool_arm");
  if (!map) return std::move(map).error();
  if (auto ok =
          map->only_keys({"tool", "lift", "signals", "home_above_mm", "pre_home_above_mm", "operating_at"});
      !ok)
    return ok;
  auto tool = map->string_or("tool", out.arm_tool);
  if (!tool) return std::move(tool).error();
  if (out.find_tool(*tool) == nullptr)
    return map->error_at("tool", fmt::format("'{}' is not one of the tools", *tool));
  auto lift = map->string_or("lift", out.lift_device);
  if (!lift) return std::move(lift).error();
  if (map->has("signals")) {
    auto signals = map->map("signals");
    if (!signals) return std::move(signals).error();
    if (auto ok = signals->only_keys({"home", "pre_home", "out_of_range"}); !ok) return ok;
    auto home = signals->string_or("home", out.arm_home_signal);
    if (!home) return std::move(home).error();
    auto pre_home = signals->string_or("pre_home", out.arm_pre_home_signal);
    if (!pre_home) return std::move(pre_home).error();
    auto out_of_range = signals->string_or("out_of_range", out.arm_out_of_range_signal);
    if (!out_of_range) return std::move(out_of_range).error();
    out.arm_home_signal = *home;
    out.arm_pre_home_signal = *pre_home;
    out.arm_out_of_range_signal = *out_of_range;
  }
  auto home = map->number_or("home_above_mm", out.home_above_mm, -1e6, 1e6);
  if (!home) return std::move(home).error();
  auto pre_home = map->number_or("pre_home_above_mm", out.pre_home_above_mm, -1e6, 1e6);
  if (!pre_home) return std::move(pre_home).error();
  if (!(*pre_home < *home)) {
    return map->error_at("pre_home_above_mm",
                         fmt::format("{} mm must be below home_above_mm ({} mm)", *pre_home, *home));
  }
  auto operating = map->string_or("operating_at", out.operating_at);
  if (!operating) return std::move(operating).error();
  if (!contains(out.places, *operating)) {
    return map->error_at("operating_at", fmt::format("'{}' is not one of the robot's places ({})", *operating,
                                                     fmt::join(out.places, ", ")));
  }
  out.arm_tool = *tool;
  out.lift_device = *lift;
  out.home_above_mm = *home;
  out.pre_home_above_mm = *pre_home;
  out.operating_at = *operating;
  return {};
}

// RobotMoverState's actual_pose is a string<64> (hubs/mir_com/msg/RobotMoverState.msg): a longer
// position could never be reported.
constexpr std::size_t kMaxPoseBytes = 64;
// MirComState's fields that hold a RobotMoverState (hubs/mir_com/msg/MirComState.msg).
constexpr std::array<std::string_view, 1> kMoverFields{"mover"};

Expected<void> mobile_platform(const YamlMap& root, StationConfig& out) {
  if (!root.has("mobile_platform")) return {};
  auto map = root.map("mobile_platform");
  if (!map) return std::move(map).error();
  if (auto ok = map->only_keys({"state", "field", "at_station", "kit", "timeout_ms"}); !ok) return ok;
  MobilePlatformConfig platform;
  auto state = map->string("state");
  if (!state) return std::move(state).error();
  if (auto valid = dds::validate_ros_topic_name(*state); !valid) {
    return map->error_at("state", valid.error().message);
  }
  platform.state_topic = *state;
  if (map->has("field")) {
    auto field = identifier(*map, "field", "");
    if (!field) return std::move(field).error();
    if (std::find(kMoverFields.begin(), kMoverFields.end(), *field) == kMoverFields.end()) {
      return map->error_at("field", fmt::format("MirComState has no RobotMoverState field '{}' (it has: {})",
                                                *field, fmt::join(kMoverFields, ", ")));
    }
    platform.field = *field;
  }
  auto at_station = map->string("at_station");
  if (!at_station) return std::move(at_station).error();
  if (at_station->size() > kMaxPoseBytes) {  // (YamlMap refuses an empty one)
    return map->error_at("at_station",
                         fmt::format("the platform's position at the station must be at most {} "
                                     "bytes (RobotMoverState's actual_pose)",
                                     kMaxPoseBytes));
  }
  platform.at_station = *at_station;
  auto kit = map->string_or("kit", platform.kit);
  if (!kit) return std::move(kit).error();
  if (!contains(out.places, *kit)) {
    return map->error_at(
        "kit", fmt::format("'{}' is not one of the robot's places ({})", *kit, fmt::join(out.places, ", ")));
  }
  if (!contains(out.frame_rests, *kit)) {
    return map->error_at("kit",
                         fmt::format("the ladder frame cannot lie at '{}' (ladder_frame.rests: {}): the kit "
                                     "brings it",
                                     *kit, fmt::join(out.frame_rests, ", ")));
  }
  if (*kit == out.robot_start) {
    return map->error_at("kit", fmt::format("the robot starts at '{}', where the kit may not be", *kit));
  }
  platform.kit = *kit;
  auto timeout = map->integer_or("timeout_ms", 1000, 10, 600'000);
  if (!timeout) return std::move(timeout).error();
  platform.timeout = std::chrono::milliseconds(*timeout);
  out.mobile_platform = std::move(platform);
  return {};
}

}  // namespace

std::string_view to_string(HubRole role) noexcept {
  switch (role) {
    case HubRole::kTool:
      return "tool_ecu";
    case HubRole::kRsp:
      return "rsp_ecu";
    case HubRole::kDock:
      return "dock_ecu";
  }
  return "?";
}

const ToolConfig* StationConfig::find_tool(std::string_view name) const noexcept {
  for (const ToolConfig& tool : tools) {
    if (tool.name == name) return &tool;
  }
  return nullptr;
}

bool StationConfig::is_location(std::string_view name) const noexcept {
  return contains(places, name) || find_tool(name) != nullptr;
}

Expected<StationConfig> parse_station_config(const YamlMap& root) {
  if (auto ok = root.only_keys({"hubs", "rate_hz", "resend_holdoff_ms", "robot", "changer", "tools",
                                "ladder_frame", "smart_tool_arm", "mobile_platform"});
      !ok) {
    return std::move(ok).error();
  }
  StationConfig out;
  out.file = root.file();
  auto rate = root.number_or("rate_hz", out.rate_hz, 1.0, 1000.0);
  if (!rate) return std::move(rate).error();
  out.rate_hz = *rate;
  auto holdoff = root.integer_or("resend_holdoff_ms", 250, 10, 60'000);
  if (!holdoff) return std::move(holdoff).error();
  out.resend_holdoff = std::chrono::milliseconds(*holdoff);
  if (auto ok = hubs(root, out); !ok) return std::move(ok).error();
  if (auto ok = robot(root, out); !ok) return std::move(ok).error();
  if (auto ok = changer(root, out); !ok) return std::move(ok).error();
  if (auto ok = tools(root, out); !ok) return std::move(ok).error();
  if (!out.is_location(out.robot_start)) {
    auto robot_map = root.map("robot");
    const std::string message =
        fmt::format("the robot cannot start at '{}': not a place ({}) nor a dock slot", out.robot_start,
                    fmt::join(out.places, ", "));
    return robot_map ? robot_map->error_at("start", message) : root.error(message);
  }
  if (auto ok = ladder_frame(root, out); !ok) return std::move(ok).error();
  if (out.find_tool(out.frame_tool) == nullptr) {
    return root.error_at(
        "tools", fmt::format("no tool '{}' to hold the ladder frame (ladder_frame.tool)", out.frame_tool));
  }
  if (auto ok = smart_tool_arm(root, out); !ok) return std::move(ok).error();
  if (auto ok = mobile_platform(root, out); !ok) return std::move(ok).error();
  if (out.find_tool(out.arm_tool) == nullptr) {
    return root.error_at("tools",
                         fmt::format("no tool '{}' with arm sensors (smart_tool_arm.tool)", out.arm_tool));
  }
  return out;
}

Expected<StationConfig> load_station_config(const std::string& path) {
  auto root = YamlMap::load_file(path);
  if (!root) return std::move(root).error();
  return parse_station_config(*root);
}

}  // namespace hubrt::sim::station
