#include "hubrt/sim/sim_world.h"

#include <fmt/format.h>

#include "hubrt/protocol/smart_tool_can.h"

namespace hubrt::sim {
namespace {

Error unknown_fault(std::string_view device, std::string_view kind, std::string_view fault,
                    std::string_view known) {
  return make_error(ErrorCode::kInvalidArgument,
                    fmt::format("{} '{}' has no fault '{}' (it has: {})", kind, device, fault, known));
}

Expected<void> smart_tool_fault(hal::fake::SmartToolSimulator& tool, const FaultRequest& request) {
  const std::string_view fault = request.fault;
  if (fault == "power_off") {
    tool.power_off();
  } else if (fault == "power_on") {
    tool.power_on();
  } else if (fault == "alarm") {
    const auto bits = static_cast<std::uint8_t>(request.value & protocol::smart_tool::alarm_bit::kAll);
    tool.raise_alarm(bits != 0 ? bits : protocol::smart_tool::alarm_bit::kOvercurrent);
  } else if (fault == "bus_off") {
    tool.set_bus_off(true);
  } else if (fault == "bus_on") {
    tool.set_bus_off(false);
  } else if (fault == "slip") {
    tool.set_joint_slip(true);
  } else if (fault == "no_slip") {
    tool.set_joint_slip(false);
  } else {
    return unknown_fault(request.device, "smart tool on CAN bus", fault,
                         "power_off, power_on, alarm, bus_off, bus_on, slip, no_slip");
  }
  return {};
}

Expected<void> lift_fault(hal::fake::LiftDrive& drive, hal::fake::LiftDriveServer& server,
                          const FaultRequest& request, Time now) {
  const std::string_view fault = request.fault;
  if (fault == "overcurrent") {
    drive.inject_overcurrent(now);
  } else if (fault == "overtemperature") {
    drive.set_overtemperature(true, now);
  } else if (fault == "cooled") {
    drive.set_overtemperature(false, now);
  } else if (fault == "blocked") {
    drive.set_blocked(true, now);
  } else if (fault == "unblocked") {
    drive.set_blocked(false, now);
  } else if (fault == "stop_answering") {
    server.set_answering(false);
  } else if (fault == "answer") {
    server.set_answering(true);
  } else if (fault == "go_down") {
    server.go_down();
  } else if (fault == "come_back") {
    return server.come_back();
  } else {
    return unknown_fault(request.device, "lift drive", fault,
                         "overcurrent, overtemperature, cooled, blocked, unblocked, stop_answering, answer, "
                         "go_down, come_back");
  }
  return {};
}

Expected<void> valve_fault(hal::fake::PneumaticValve& valve, std::size_t confirms,
                           const FaultRequest& request) {
  const std::string_view fault = request.fault;
  if (fault == "stick" || fault == "unstick") {
    valve.stick(fault == "stick");
    return {};
  }
  if (fault == "fail_confirm" || fault == "repair_confirm") {
    if (request.value >= confirms) {
      return make_error(ErrorCode::kInvalidArgument,
                        fmt::format("valve '{}' has {} confirm sensor(s); there is no index {}",
                                    request.device, confirms, request.value));
    }
    if (fault == "fail_confirm") {
      valve.fail_confirm(request.value, true);
    } else {
      valve.repair_confirm(request.value);
    }
    return {};
  }
  return unknown_fault(request.device, "valve", fault, "stick, unstick, fail_confirm, repair_confirm");
}

// The MiR100 simulator: the REST server's faults, the server going away, the platform's own error
// and battery.
Expected<void> mir_fault(hal::fake::MirPlatform& platform, hal::fake::MirSimServer& server,
                         const FaultRequest& request, Time now) {
  const std::string_view fault = request.fault;
  if (const auto kind = hal::fake::parse_mir_fault(fault); kind.is_ok()) {
    server.set_fault(kind.value());
  } else if (fault == "go_down") {
    server.go_down();
  } else if (fault == "come_back") {
    return server.come_back();
  } else if (fault == "platform_error") {
    platform.inject_error(request.value == 0 ? 3001 : static_cast<int>(request.value),
                          "Simulated platform error", now);
  } else if (fault == "battery") {
    platform.set_battery_percent(request.value);
  } else {
    return unknown_fault(request.device, "MiR100 platform", fault,
                         "server_error, unauthorized, slow, stop_answering, malformed_json, answer, go_down, "
                         "come_back, platform_error, battery");
  }
  return {};
}

}  // namespace

Expected<void> apply_input(hal::fake::FakeBackend& fake, std::string_view signal, bool active) {
  if (auto* sensor = fake.dock_sensor(signal); sensor != nullptr) {
    sensor->set_occupied(active);
  } else if (auto* input = fake.input(signal); input != nullptr) {
    input->set(active);
  } else if (auto* supply = fake.pressure_supply(signal); supply != nullptr) {
    if (active) {
      supply->restore();
    } else {
      supply->drop();
    }
  } else {
    return make_error(ErrorCode::kNotFound,
                      fmt::format("'{}' is not a simulated input or pressure supply", signal));
  }
  return {};
}

Expected<void> apply_badge(hal::fake::FakeBackend& fake, std::string_view reader, std::string_view text) {
  auto* simulated = fake.badge_reader(reader);
  if (simulated == nullptr) {
    return make_error(ErrorCode::kNotFound, fmt::format("'{}' is not a simulated RFID reader", reader));
  }
  simulated->present(text);
  return {};
}

Expected<void> apply_fault(hal::fake::FakeBackend& fake, const hal::BoardConfig& board,
                           const FaultRequest& request, Time now) {
  if (auto* platform = fake.mir_platform(request.device); platform != nullptr) {
    return mir_fault(*platform, *fake.mir_server(request.device), request, now);
  }
  if (auto* tool = fake.smart_tool(request.device); tool != nullptr) return smart_tool_fault(*tool, request);
  if (auto* drive = fake.lift_drive(request.device); drive != nullptr) {
    auto* server = fake.lift_drive_server(request.device);
    if (server == nullptr) {
      return make_error(ErrorCode::kNotFound, fmt::format("lift drive '{}' has no server", request.device));
    }
    return lift_fault(*drive, *server, request, now);
  }
  if (auto* supply = fake.pressure_supply(request.device); supply != nullptr) {
    if (request.fault == "drop") {
      supply->drop();
    } else if (request.fault == "restore") {
      supply->restore();
    } else {
      return unknown_fault(request.device, "pressure supply", request.fault, "drop, restore");
    }
    return {};
  }
  if (auto* valve = fake.valve(request.device); valve != nullptr) {
    std::size_t confirms = 0;
    if (board.simulation) {
      for (const auto& config : board.simulation->valves) {
        if (config.output == request.device) confirms = config.confirms.size();
      }
    }
    return valve_fault(*valve, confirms, request);
  }
  return make_error(
      ErrorCode::kNotFound,
      fmt::format("'{}' is not a simulated device (smart tool bus, lift drive, MiR100, pressure supply "
                  "or valve) of this board",
                  request.device));
}

}  // namespace hubrt::sim
