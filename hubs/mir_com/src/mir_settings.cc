#include "mir_settings.h"

#include <algorithm>

#include <fmt/format.h>

#include "hubrt/protocol/mir_rest.h"

namespace hubrt::mir_com {
namespace {

Expected<MirLinkSettings> parse_link(const config::YamlMap& settings) {
  MirLinkSettings link;
  auto device = settings.string("device");
  if (!device) return std::move(device).error();
  link.device = *device;
  auto robot = settings.string("robot_name");
  if (!robot) return std::move(robot).error();
  if (!protocol::mir::valid_position_name(*robot)) {
    return settings.error_at("robot_name",
                             fmt::format("'{}': 1 to 40 of letters, digits, '_', '-', '.', ' '", *robot));
  }
  link.robot_name = *robot;
  auto poll = settings.integer_or("poll_ms", 200, 20, 5000);
  if (!poll) return std::move(poll).error();
  link.poll = std::chrono::milliseconds(*poll);
  auto within = settings.integer_or("answer_within_ms", 2000, 100, 60'000);
  if (!within) return std::move(within).error();
  link.answer_within = std::chrono::milliseconds(*within);
  if (link.answer_within <= link.poll) {
    return settings.error_at("answer_within_ms", "must be longer than poll_ms");
  }
  return link;
}

}  // namespace

Expected<RobotMoverSettings> parse_robot_mover_settings(const config::NodeConfig& node) {
  const config::YamlMap& settings = node.settings;
  if (auto ok = settings.only_keys({"type", "device", "robot_name", "poll_ms", "answer_within_ms",
                                    "move_mission", "position_parameter"});
      !ok) {
    return std::move(ok).error();
  }
  RobotMoverSettings out;
  auto link = parse_link(settings);
  if (!link) return std::move(link).error();
  out.link = std::move(*link);
  auto mission = settings.string("move_mission");
  if (!mission) return std::move(mission).error();
  if (!protocol::mir::valid_guid(*mission)) {
    return settings.error_at("move_mission",
                             fmt::format("'{}' is not a MiR guid (hex digits and '-')", *mission));
  }
  out.move_mission = *mission;
  auto parameter = settings.string_or("position_parameter", "Position");
  if (!parameter) return std::move(parameter).error();
  if (!protocol::mir::valid_position_name(*parameter)) {
    return settings.error_at("position_parameter", fmt::format("'{}' is not a parameter id", *parameter));
  }
  out.position_parameter = *parameter;
  return out;
}

Expected<PoseSaverSettings> parse_pose_saver_settings(const config::NodeConfig& node) {
  const config::YamlMap& settings = node.settings;
  if (auto ok = settings.only_keys({"type", "device", "robot_name", "poll_ms", "answer_within_ms"}); !ok) {
    return std::move(ok).error();
  }
  auto link = parse_link(settings);
  if (!link) return std::move(link).error();
  return PoseSaverSettings{std::move(*link)};
}

void add_requirements(const MirLinkSettings& settings, hal::BoardRequirements& requirements) {
  if (std::find(requirements.http_devices.begin(), requirements.http_devices.end(), settings.device) ==
      requirements.http_devices.end()) {
    requirements.http_devices.push_back(settings.device);
  }
}

}  // namespace hubrt::mir_com
