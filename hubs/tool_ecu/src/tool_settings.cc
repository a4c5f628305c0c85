#include "tool_settings.h"

#include <cmath>
#include <set>

#include <fmt/format.h>

#include "hubrt/protocol/lift_drive_modbus.h"

namespace hubrt::tool_ecu {
namespace {

Expected<void> usable_name(const config::YamlMap& where, std::string_view key, const std::string& name,
                           std::string_view what) {
  if (config::is_ros_name_token(name)) return {};
  return where.error_at(key, fmt::format("'{}' is not a usable {} name: use letters, digits and underscores, "
                                         "starting with a letter",
                                         name, what));
}

// Reads `key` as a count of `unit` (e.g. 0.01 Nm) from a value given in whole units, exactly.
Expected<std::uint16_t> scaled(const config::YamlMap& map, std::string_view key, double scale, double min,
                               double max) {
  auto value = map.number(key, min, max);
  if (!value) return std::move(value).error();
  return static_cast<std::uint16_t>(std::lround(*value * scale));
}

Expected<ToolProgram> parse_program(const std::string& name, const config::YamlMap& map) {
  if (auto ok = map.only_keys({"number", "torque_nm", "angle_min_deg", "angle_max_deg"}); !ok) {
    return std::move(ok).error();
  }
  if (auto ok = usable_name(map, "number", name, "program"); !ok) return std::move(ok).error();
  if (name == "unknown") {
    // The State's selected_program reads "unknown" when the controller's status is stale.
    return map.error_at("number",
                        "'unknown' is reserved: the State says selected_program 'unknown' "
                        "when the controller's status is not current");
  }
  ToolProgram program{name, {}};
  auto number = map.integer("number", 1, 255);
  if (!number) return std::move(number).error();
  program.program.number = static_cast<std::uint8_t>(*number);
  auto torque = scaled(map, "torque_nm", 100.0, 0.01, 655.35);
  if (!torque) return std::move(torque).error();
  program.program.torque_target_cnm = *torque;
  auto angle_min = scaled(map, "angle_min_deg", 10.0, 0.0, 6553.5);
  if (!angle_min) return std::move(angle_min).error();
  program.program.angle_min_ddeg = *angle_min;
  auto angle_max = scaled(map, "angle_max_deg", 10.0, 0.0, 6553.5);
  if (!angle_max) return std::move(angle_max).error();
  program.program.angle_max_ddeg = *angle_max;
  if (program.program.angle_max_ddeg < program.program.angle_min_ddeg) {
    return map.error_at("angle_max_deg", "the angle window's maximum is below its minimum");
  }
  return program;
}

Expected<void> parse_signals(const config::YamlMap& node, SmartToolSettings& s) {
  if (!node.has("signals")) return {};
  auto signals = node.map("signals");
  if (!signals) return std::move(signals).error();
  if (auto ok = signals->only_keys({"run_forward", "run_reverse", "button_forward", "button_reverse",
                                    "torque_reached", "summary_alarm", "arm_home", "arm_pre_home",
                                    "arm_out_of_range"});
      !ok) {
    return std::move(ok).error();
  }
  const std::pair<std::string_view, std::string*> fields[] = {{"run_forward", &s.run_forward},
                                                              {"run_reverse", &s.run_reverse},
                                                              {"button_forward", &s.button_forward},
                                                              {"button_reverse", &s.button_reverse},
                                                              {"torque_reached", &s.torque_reached},
                                                              {"summary_alarm", &s.summary_alarm},
                                                              {"arm_home", &s.arm.home},
                                                              {"arm_pre_home", &s.arm.pre_home},
                                                              {"arm_out_of_range", &s.arm.out_of_range}};
  for (const auto& [key, target] : fields) {
    auto value = signals->string_or(key, *target);
    if (!value) return std::move(value).error();
    *target = std::move(*value);
  }
  return {};
}

}  // namespace

Expected<SmartToolSettings> parse_smart_tool_settings(const config::NodeConfig& node) {
  const config::YamlMap& map = node.settings;
  if (auto ok = map.only_keys({"type", "bus", "node_id", "signals", "robot_state", "operator_state",
                               "programs", "manual_program", "start_timeout_ms", "resend_ms"});
      !ok) {
    return std::move(ok).error();
  }
  SmartToolSettings s;
  auto bus = map.string_or("bus", s.bus);
  if (!bus) return std::move(bus).error();
  s.bus = std::move(*bus);
  auto node_id = map.integer_or("node_id", s.node_id, protocol::smart_tool::kMinNodeId,
                                protocol::smart_tool::kMaxNodeId);
  if (!node_id) return std::move(node_id).error();
  s.node_id = static_cast<std::uint8_t>(*node_id);
  if (auto ok = parse_signals(map, s); !ok) return std::move(ok).error();
  auto robot = map.string_or("robot_state", s.robot_state);
  if (!robot) return std::move(robot).error();
  s.robot_state = std::move(*robot);
  auto operator_state = map.string_or("operator_state", "");
  if (!operator_state) return std::move(operator_state).error();
  s.operator_state = std::move(*operator_state);

  auto programs = map.named_maps("programs");
  if (!programs) return std::move(programs).error();
  if (programs->empty() || programs->size() > SmartToolSettings::kMaxPrograms) {
    return map.error_at("programs", fmt::format("a smart tool has 1 to {} programs, got {}",
                                                SmartToolSettings::kMaxPrograms, programs->size()));
  }
  std::set<unsigned> numbers;
  for (const auto& [name, program_map] : *programs) {
    auto program = parse_program(name, program_map);
    if (!program) return std::move(program).error();
    if (!numbers.insert(program->program.number).second) {
      // One number, one set of parameters: the controller reports only the number it selected.
      return program_map.error_at("number",
                                  fmt::format("program number {} is used twice", program->program.number));
    }
    s.programs.push_back(std::move(*program));
  }
  if (map.has("manual_program")) {
    auto manual = map.string("manual_program");
    if (!manual) return std::move(manual).error();
    for (std::size_t i = 0; i < s.programs.size(); ++i) {
      if (s.programs[i].name == *manual) s.manual_program = static_cast<int>(i);
    }
    if (s.manual_program < 0) {
      return map.error_at("manual_program", fmt::format("'{}' is not one of the programs", *manual));
    }
  }
  auto start_ms = map.integer_or("start_timeout_ms", 500, 50, 10'000);
  if (!start_ms) return std::move(start_ms).error();
  s.start_timeout = std::chrono::milliseconds(*start_ms);
  auto resend_ms = map.integer_or("resend_ms", 300, 20, 10'000);
  if (!resend_ms) return std::move(resend_ms).error();
  s.resend_after = std::chrono::milliseconds(*resend_ms);
  return s;
}

Expected<LiftSettings> parse_lift_settings(const config::NodeConfig& node) {
  const config::YamlMap& map = node.settings;
  if (auto ok = map.only_keys(
          {"type", "device", "positions", "speed_mm_s", "drive_watchdog_ms", "answer_within_ms", "poll_ms"});
      !ok) {
    return std::move(ok).error();
  }
  LiftSettings s;
  auto device = map.string_or("device", s.device);
  if (!device) return std::move(device).error();
  s.device = std::move(*device);
  auto positions = map.map("positions");
  if (!positions) return std::move(positions).error();
  const std::vector<std::string> names = positions->keys();
  if (names.empty() || names.size() > LiftSettings::kMaxPositions) {
    return map.error_at("positions", fmt::format("a lift has 1 to {} named positions, got {}",
                                                 LiftSettings::kMaxPositions, names.size()));
  }
  for (const std::string& name : names) {
    if (auto ok = usable_name(*positions, name, name, "position"); !ok) return std::move(ok).error();
    auto tenth = scaled(*positions, name, 10.0, 0.0, 6553.5);
    if (!tenth) return std::move(tenth).error();
    s.positions.push_back(LiftPosition{name, *tenth});
  }
  auto speed = map.integer_or("speed_mm_s", s.speed_mm_s, 1, 65535);
  if (!speed) return std::move(speed).error();
  s.speed_mm_s = static_cast<std::uint16_t>(*speed);
  auto watchdog =
      map.integer_or("drive_watchdog_ms", s.drive_watchdog_ms, 0, protocol::lift_drive::kMaxWatchdogMs);
  if (!watchdog) return std::move(watchdog).error();
  s.drive_watchdog_ms = static_cast<std::uint16_t>(*watchdog);
  auto answer = map.integer_or("answer_within_ms", 500, 100, 60'000);
  if (!answer) return std::move(answer).error();
  s.answer_within = std::chrono::milliseconds(*answer);
  auto poll = map.integer_or("poll_ms", 20, 1, 1000);
  if (!poll) return std::move(poll).error();
  s.poll_interval = std::chrono::milliseconds(*poll);
  return s;
}

void add_requirements(const SmartToolSettings& s, hal::BoardRequirements& requirements) {
  requirements.outputs.insert(requirements.outputs.end(), {s.run_forward, s.run_reverse});
  requirements.inputs.insert(requirements.inputs.end(),
                             {s.button_forward, s.button_reverse, s.torque_reached, s.summary_alarm,
                              s.arm.home, s.arm.pre_home, s.arm.out_of_range});
  requirements.can_buses.push_back(s.bus);
}

void add_requirements(const LiftSettings& s, hal::BoardRequirements& requirements) {
  requirements.modbus_devices.push_back(s.device);
}

}  // namespace hubrt::tool_ecu
