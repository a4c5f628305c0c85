#include "rsp_settings.h"

#include <algorithm>
#include <set>

#include <fmt/format.h>

namespace hubrt::rsp_ecu {
namespace {

Expected<std::vector<ToolLine>> parse_tool_lines(const config::YamlMap& settings) {
  auto map = settings.map("tool_id");
  if (!map) return std::move(map).error();
  const std::vector<std::string> tools = map->keys();
  if (tools.empty() || tools.size() > RspSettings::kMaxTools) {
    return settings.error_at("tool_id", fmt::format("a tool changer has 1 to {} tool-ID lines, got {}",
                                                    RspSettings::kMaxTools, tools.size()));
  }
  std::vector<ToolLine> lines;
  for (const std::string& tool : tools) {
    if (!config::is_ros_name_token(tool)) {
      return map->error_at(tool, fmt::format("'{}' is not a usable tool name: use letters, digits and "
                                             "underscores, starting with a letter",
                                             tool));
    }
    // These two are what State.tool says when no line, or more than one, is set.
    if (tool == "none" || tool == "undefined")
      return map->error_at(tool, fmt::format("'{}' is reserved, not a tool name", tool));
    auto signal = map->string(tool);
    if (!signal) return std::move(signal).error();
    lines.push_back(ToolLine{tool, *signal});
  }
  return lines;
}

}  // namespace

Expected<RspSettings> parse_rsp_settings(const config::NodeConfig& node) {
  const config::YamlMap& s = node.settings;
  if (auto ok = s.only_keys({"type", "dock", "lock_valve", "gripper_valve", "tool_id", "gripper_confirm",
                             "pressure_switch", "gripper_tool", "lock_actuation_ms", "gripper_confirm_ms"});
      !ok) {
    return std::move(ok).error();
  }
  RspSettings out;
  auto dock = s.string_or("dock", "dock");
  if (!dock) return std::move(dock).error();
  out.dock_subscription = std::move(*dock);
  auto lock = s.string("lock_valve");
  if (!lock) return std::move(lock).error();
  out.lock_valve = std::move(*lock);
  auto gripper = s.string("gripper_valve");
  if (!gripper) return std::move(gripper).error();
  out.gripper_valve = std::move(*gripper);
  auto tools = parse_tool_lines(s);
  if (!tools) return std::move(tools).error();
  out.tool_lines = std::move(*tools);

  auto confirms = s.list_of_strings("gripper_confirm");
  if (!confirms) return std::move(confirms).error();
  if (confirms->size() != 2) {
    return s.error_at("gripper_confirm", fmt::format("expected the two confirm inputs [A, B], got {} entries",
                                                     confirms->size()));
  }
  out.gripper_confirms = {(*confirms)[0], (*confirms)[1]};
  auto pressure = s.string("pressure_switch");
  if (!pressure) return std::move(pressure).error();
  out.pressure_switch = std::move(*pressure);

  auto gripper_tool = s.string_or("gripper_tool", "ladder_frame_tool");
  if (!gripper_tool) return std::move(gripper_tool).error();
  const bool known = std::any_of(out.tool_lines.begin(), out.tool_lines.end(),
                                 [&](const ToolLine& line) { return line.tool == *gripper_tool; });
  if (!known) {
    return s.has("gripper_tool")
               ? s.error_at("gripper_tool",
                            fmt::format("'{}' is not one of the tools under tool_id", *gripper_tool))
               : s.error(fmt::format("gripper_tool: the default '{}' is not one of the tools under tool_id; "
                                     "name the tool that carries the gripper",
                                     *gripper_tool));
  }
  out.gripper_tool = std::move(*gripper_tool);

  auto lock_ms = s.integer_or("lock_actuation_ms", 200, 1, 10'000);
  if (!lock_ms) return std::move(lock_ms).error();
  out.lock_actuation = std::chrono::milliseconds(*lock_ms);
  auto confirm_ms = s.integer_or("gripper_confirm_ms", 500, 1, 10'000);
  if (!confirm_ms) return std::move(confirm_ms).error();
  out.gripper_confirm = std::chrono::milliseconds(*confirm_ms);

  // Every signal once: a line used twice would make two of the node's inputs read the same wire.
  std::set<std::string> seen;
  const auto once = [&](const std::string& signal) { return seen.insert(signal).second; };
  std::vector<std::string> all{out.lock_valve, out.gripper_valve, out.gripper_confirms[0],
                               out.gripper_confirms[1], out.pressure_switch};
  for (const ToolLine& line : out.tool_lines) all.push_back(line.signal);
  for (const std::string& signal : all) {
    if (!once(signal)) return s.error(fmt::format("signal '{}' is used twice by this node", signal));
  }
  return out;
}

void add_requirements(const RspSettings& settings, hal::BoardRequirements& requirements) {
  requirements.outputs.push_back(settings.lock_valve);
  requirements.outputs.push_back(settings.gripper_valve);
  for (const ToolLine& line : settings.tool_lines) requirements.inputs.push_back(line.signal);
  for (const std::string& confirm : settings.gripper_confirms) requirements.inputs.push_back(confirm);
  requirements.inputs.push_back(settings.pressure_switch);
}

}  // namespace hubrt::rsp_ecu
