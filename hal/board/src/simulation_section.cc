// simulation: which simulators the fake backend wires to which signals.
#include <map>

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal::board_detail {
namespace {

constexpr std::int64_t kMaxActuationMs = 60'000;
constexpr std::int64_t kMaxBounceMs = 1'000;

// Which simulator drives each input (or listens to each output): at most one each.
class Claims {
 public:
  // `map`/`key` locate the error; `by` says who claims, e.g. "valve 'rsp.gripper_valve' (line 40)".
  Expected<void> claim(const YamlMap& map, std::string_view key, const std::string& signal, std::string by) {
    const auto [existing, inserted] = claims_.emplace(signal, std::move(by));
    if (inserted) return {};
    const std::string message = fmt::format("'{}' is already driven by {}", signal, existing->second);
    return key.empty() ? map.error(message) : map.error_at(key, message);
  }

 private:
  std::map<std::string, std::string> claims_;
};

Expected<void> require(const YamlMap& map, std::string_view key, const std::string& signal,
                       const BoardConfig& board, bool want_input) {
  const BoardInput* input = board.find_input(signal);
  const BoardOutput* output = board.find_output(signal);
  if (want_input ? input != nullptr : output != nullptr) return {};
  std::string message;
  if (want_input && output != nullptr) {
    message =
        fmt::format("'{}' is declared as an output (line {}), not an input", signal, output->where.line);
  } else if (!want_input && input != nullptr) {
    message = fmt::format("'{}' is declared as an input (line {}), not an output", signal, input->where.line);
  } else {
    message = fmt::format("'{}' is not an {} of this board", signal, want_input ? "input" : "output");
  }
  return key.empty() ? map.error(message) : map.error_at(key, message);
}

Expected<void> parse_supplies(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim,
                              Claims& claims) {
  auto supplies = simulation.named_maps("pressure_supplies");
  if (!supplies) return std::move(supplies).error();
  for (const auto& [name, map] : *supplies) {
    if (!valid_identifier(name))
      return map.error("not a valid supply name (lower-case letters, digits, '_', '-')");
    if (auto ok = map.only_keys({"switch", "ok"}); !ok) return ok;
    SimPressureSupplyConfig supply;
    supply.name = name;
    supply.where = where(map);
    auto input = map.string("switch");
    if (!input) return std::move(input).error();
    supply.switch_input = *input;
    if (auto ok = require(map, "switch", supply.switch_input, board, true); !ok) return ok;
    if (auto ok = claims.claim(map, "switch", supply.switch_input,
                               declared_at("pressure supply", name, supply.where));
        !ok) {
      return ok;
    }
    auto pressure_ok = map.boolean_or("ok", true);
    if (!pressure_ok) return std::move(pressure_ok).error();
    supply.ok = *pressure_ok;
    sim.pressure_supplies.push_back(std::move(supply));
  }
  return {};
}

Expected<void> parse_valves(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim,
                            Claims& claims) {
  auto valves = simulation.named_maps("valves");
  if (!valves) return std::move(valves).error();
  for (const auto& [output, map] : *valves) {
    if (auto ok = map.only_keys({"confirms", "supply", "actuation_ms"}); !ok) return ok;
    SimValveConfig valve;
    valve.output = output;
    valve.where = where(map);
    const std::string who = declared_at("valve", output, valve.where);
    if (auto ok = require(map, "", output, board, false); !ok) return ok;
    if (auto ok = claims.claim(map, "", output, who); !ok) return ok;
    auto confirms = map.list_of_strings("confirms", /*optional=*/true);
    if (!confirms) return std::move(confirms).error();
    for (const std::string& confirm : *confirms) {
      if (auto ok = require(map, "confirms", confirm, board, true); !ok) return ok;
      if (auto ok = claims.claim(map, "confirms", confirm, who); !ok) return ok;
    }
    valve.confirms = std::move(*confirms);
    auto supply = map.string_or("supply", "");
    if (!supply) return std::move(supply).error();
    if (!supply->empty()) {
      const bool known = std::any_of(sim.pressure_supplies.begin(), sim.pressure_supplies.end(),
                                     [&](const SimPressureSupplyConfig& s) { return s.name == *supply; });
      if (!known) {
        return map.error_at(
            "supply", fmt::format("unknown pressure supply '{}' (simulation.pressure_supplies)", *supply));
      }
    }
    valve.supply = *supply;
    auto actuation = map.integer("actuation_ms", 0, kMaxActuationMs);
    if (!actuation) return std::move(actuation).error();
    valve.actuation = std::chrono::milliseconds(*actuation);
    sim.valves.push_back(std::move(valve));
  }
  return {};
}

Expected<void> parse_dock_sensors(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim,
                                  Claims& claims) {
  auto sensors = simulation.named_maps("dock_sensors");
  if (!sensors) return std::move(sensors).error();
  for (const auto& [input, map] : *sensors) {
    if (auto ok = map.only_keys({"bounce_ms", "occupied"}); !ok) return ok;
    SimDockSensorConfig sensor;
    sensor.input = input;
    sensor.where = where(map);
    if (auto ok = require(map, "", input, board, true); !ok) return ok;
    if (auto ok = claims.claim(map, "", input, declared_at("dock sensor", input, sensor.where)); !ok)
      return ok;
    auto bounce = map.integer_or("bounce_ms", 0, 0, kMaxBounceMs);
    if (!bounce) return std::move(bounce).error();
    sensor.bounce = std::chrono::milliseconds(*bounce);
    auto occupied = map.boolean_or("occupied", false);
    if (!occupied) return std::move(occupied).error();
    sensor.occupied = *occupied;
    sim.dock_sensors.push_back(std::move(sensor));
  }
  return {};
}

Expected<void> parse_input_levels(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim,
                                  Claims& claims) {
  auto inputs = simulation.map("inputs");
  if (!inputs) return std::move(inputs).error();
  for (const std::string& signal : inputs->keys()) {
    SimInputLevel level;
    level.input = signal;
    level.where = where(inputs->node()[signal].Mark());
    if (auto ok = require(*inputs, signal, signal, board, true); !ok) return ok;
    if (auto ok = claims.claim(*inputs, signal, signal,
                               declared_at("simulation.inputs entry", signal, level.where));
        !ok) {
      return ok;
    }
    auto active = inputs->boolean(signal);
    if (!active) return std::move(active).error();
    level.active = *active;
    sim.inputs.push_back(std::move(level));
  }
  return {};
}

Expected<void> parse_can_devices(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim) {
  auto devices = simulation.named_maps("can");
  if (!devices) return std::move(devices).error();
  for (const auto& [bus, map] : *devices) {
    if (auto ok = map.only_keys({"simulator", "node_id"}); !ok) return ok;
    if (board.find_can(bus) == nullptr)
      return map.error(fmt::format("'{}' is not a CAN bus of this board", bus));
    SimCanDevice device;
    device.bus = bus;
    device.where = where(map);
    auto simulator = map.choice("simulator", {"smart_tool"});
    if (!simulator) return std::move(simulator).error();
    device.simulator = *simulator;
    auto node_id = map.integer_or("node_id", 0, 1, 127);
    if (!node_id) return std::move(node_id).error();
    device.node_id = static_cast<unsigned>(*node_id);
    sim.can.push_back(std::move(device));
  }
  return {};
}

Expected<void> parse_modbus_devices(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim) {
  auto devices = simulation.named_maps("modbus");
  if (!devices) return std::move(devices).error();
  for (const auto& [name, map] : *devices) {
    if (auto ok = map.only_keys({"simulator"}); !ok) return ok;
    const BoardModbusDevice* modbus = board.find_modbus(name);
    if (modbus == nullptr) return map.error(fmt::format("'{}' is not a Modbus device of this board", name));
    if (!std::holds_alternative<ModbusTcpEndpoint>(modbus->config.endpoint)) {
      return map.error(
          fmt::format("Modbus device '{}' (line {}) must use tcp: the simulator is a Modbus/TCP server", name,
                      modbus->where.line));
    }
    SimModbusDevice device;
    device.device = name;
    device.where = where(map);
    auto simulator = map.choice("simulator", {"lift_drive"});
    if (!simulator) return std::move(simulator).error();
    device.simulator = *simulator;
    sim.modbus.push_back(std::move(device));
  }
  return {};
}

// http.<device>: {simulator: mir100, robot_name, speed_m_s, positions: {name: [x, y, yaw_deg]}}.
Expected<void> parse_http_devices(const YamlMap& simulation, BoardConfig& board, SimulationConfig& sim) {
  auto devices = simulation.named_maps("http");
  if (!devices) return std::move(devices).error();
  for (const auto& [name, map] : *devices) {
    if (auto ok = map.only_keys({"simulator", "robot_name", "speed_m_s", "positions"}); !ok) return ok;
    const BoardHttpDevice* http = board.find_http(name);
    if (http == nullptr) return map.error(fmt::format("'{}' is not an HTTP device of this board", name));
    SimHttpDevice device;
    device.device = name;
    device.where = where(map);
    auto simulator = map.choice("simulator", {"mir100"});
    if (!simulator) return std::move(simulator).error();
    device.simulator = *simulator;
    auto robot = map.string_or("robot_name", "MiR_sim");
    if (!robot) return std::move(robot).error();
    device.robot_name = *robot;
    auto speed = map.number_or("speed_m_s", 1.0, 0.05, 2.0);
    if (!speed) return std::move(speed).error();
    device.speed_m_s = *speed;
    auto positions = map.map("positions");
    if (!positions) return std::move(positions).error();
    for (const std::string& position : positions->keys()) {
      const YAML::Node node = positions->node()[position];
      if (!node.IsSequence() || node.size() != 3) {
        return positions->error_at(position, "a position is [x_m, y_m, yaw_deg]");
      }
      SimMirPosition p;
      p.name = position;
      p.x = node[0].as<double>();
      p.y = node[1].as<double>();
      p.yaw_deg = node[2].as<double>();
      device.positions.push_back(p);
    }
    if (device.positions.empty()) return map.error_at("positions", "name at least one position");
    sim.http.push_back(std::move(device));
  }
  return {};
}

// Every line must exist on the fake chips, and every Modbus device needs its simulator.
Expected<void> check_complete(const YamlMap& simulation, const BoardConfig& board,
                              const SimulationConfig& sim) {
  const auto check_line = [&](const std::string& kind, const std::string& signal, unsigned line,
                              SourceLocation at) -> Expected<void> {
    if (line < sim.chip_lines) return {};
    return simulation.error_at("chip_lines",
                               fmt::format("the fake chips have {} lines but {} '{}' (line {}) uses line {}",
                                           sim.chip_lines, kind, signal, at.line, line));
  };
  for (const BoardInput& input : board.inputs) {
    if (auto ok = check_line("input", input.config.signal, input.config.line, input.where); !ok) return ok;
  }
  for (const BoardOutput& output : board.outputs) {
    if (auto ok = check_line("output", output.config.signal, output.config.line, output.where); !ok)
      return ok;
  }
  for (const BoardModbusDevice& device : board.modbus) {
    const bool simulated = std::any_of(sim.modbus.begin(), sim.modbus.end(), [&](const SimModbusDevice& d) {
      return d.device == device.config.device;
    });
    if (!simulated) {
      return simulation.error(
          fmt::format("Modbus device '{}' (line {}) has no simulator: add simulation.modbus.{}",
                      device.config.device, device.where.line, device.config.device));
    }
  }
  for (const BoardHttpDevice& device : board.http) {
    const bool simulated = std::any_of(sim.http.begin(), sim.http.end(), [&](const SimHttpDevice& d) {
      return d.device == device.config.device;
    });
    if (!simulated) {
      return simulation.error(
          fmt::format("HTTP device '{}' (line {}) has no simulator: add simulation.http.{}",
                      device.config.device, device.where.line, device.config.device));
    }
  }
  return {};
}

}  // namespace

Expected<void> parse_simulation(const YamlMap& simulation, BoardConfig& board) {
  if (auto ok = simulation.only_keys(
          {"chip_lines", "pressure_supplies", "valves", "dock_sensors", "inputs", "can", "modbus", "http"});
      !ok) {
    return ok;
  }
  SimulationConfig sim;
  auto chip_lines = simulation.integer_or("chip_lines", 32, 1, 512);
  if (!chip_lines) return std::move(chip_lines).error();
  sim.chip_lines = static_cast<unsigned>(*chip_lines);
  Claims claims;
  if (simulation.has("pressure_supplies")) {
    if (auto ok = parse_supplies(simulation, board, sim, claims); !ok) return ok;
  }
  if (simulation.has("valves")) {
    if (auto ok = parse_valves(simulation, board, sim, claims); !ok) return ok;
  }
  if (simulation.has("dock_sensors")) {
    if (auto ok = parse_dock_sensors(simulation, board, sim, claims); !ok) return ok;
  }
  if (simulation.has("inputs")) {
    if (auto ok = parse_input_levels(simulation, board, sim, claims); !ok) return ok;
  }
  if (simulation.has("can")) {
    if (auto ok = parse_can_devices(simulation, board, sim); !ok) return ok;
  }
  if (simulation.has("modbus")) {
    if (auto ok = parse_modbus_devices(simulation, board, sim); !ok) return ok;
  }
  if (simulation.has("http")) {
    if (auto ok = parse_http_devices(simulation, board, sim); !ok) return ok;
  }
  if (auto ok = check_complete(simulation, board, sim); !ok) return ok;
  board.simulation = std::move(sim);
  return {};
}

}  // namespace hubrt::hal::board_detail
