#include "hubrt/packaging/board_facts.h"

#include <algorithm>
#include <cmath>
#include <variant>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

namespace hubrt::packaging {

std::chrono::seconds watchdog_for_rate(double rate_hz) {
  constexpr double kPeriods = 5.0;
  constexpr double kMinimumSeconds = 2.0;
  const double seconds = std::max(kMinimumSeconds, kPeriods / rate_hz);
  return std::chrono::seconds(static_cast<std::int64_t>(std::ceil(seconds)));
}

Expected<BoardFacts> package_facts(const hal::BoardConfig& board, const config::HubConfig& hub) {
  const auto refuse = [&board](const std::string& why) {
    return make_error(ErrorCode::kInvalidArgument,
                      fmt::format("{}: cannot package board '{}': {}", board.file, board.name, why));
  };
  if (board.simulation) return refuse("it is a simulation board (it runs on the fake backend, not on a Pi)");
  if (board.arch != "arm64" && board.arch != "armhf") {
    return refuse(fmt::format("arch '{}' is not a Raspberry Pi target (arm64 or armhf)", board.arch));
  }
  if (board.hubs.size() != 1) {
    return refuse(fmt::format("it is wired for {} hubs; a package runs exactly one", board.hubs.size()));
  }
  if (hub.type != board.hubs.front()) {
    return refuse(fmt::format("the hub configuration given is for hub type '{}', the board runs '{}'",
                              hub.type, board.hubs.front()));
  }

  BoardFacts facts;
  facts.board = board.name;
  facts.description = board.description;
  facts.arch = board.arch;
  facts.hub = hub.type;
  facts.rate_hz = hub.rate_hz;
  facts.watchdog = watchdog_for_rate(hub.rate_hz);
  facts.gpio = !board.inputs.empty() || !board.outputs.empty();
  facts.http = !board.http.empty();
  for (const hal::BoardCanBus& can : board.can) {
    facts.can.push_back({can.config.bus, can.config.interface, can.config.bitrate});
  }
  for (const hal::BoardModbusDevice& device : board.modbus) {
    if (const auto* rtu = std::get_if<hal::ModbusRtuEndpoint>(&device.config.endpoint)) {
      if (std::find(facts.serial_devices.begin(), facts.serial_devices.end(), rtu->device) ==
          facts.serial_devices.end()) {
        facts.serial_devices.push_back(rtu->device);
      }
    }
  }
  for (const hal::BoardBadgeReader& reader : board.badge_readers) {
    auto& devices =
        reader.config.kind == hal::BadgeReaderKind::kSerial ? facts.serial_devices : facts.input_devices;
    if (std::find(devices.begin(), devices.end(), reader.config.device) == devices.end()) {
      devices.push_back(reader.config.device);
    }
  }
  return facts;
}

std::string to_json(const BoardFacts& facts) {
  nlohmann::json can = nlohmann::json::array();
  for (const PackagedCanInterface& interface : facts.can) {
    can.push_back(
        {{"bus", interface.bus}, {"interface", interface.interface}, {"bitrate", interface.bitrate}});
  }
  const nlohmann::json json = {
      {"board", facts.board},
      {"description", facts.description},
      {"arch", facts.arch},
      {"hub", facts.hub},
      {"rate_hz", facts.rate_hz},
      {"watchdog_sec", facts.watchdog.count()},
      {"gpio", facts.gpio},
      {"http", facts.http},
      {"can", can},
      {"serial_devices", facts.serial_devices},
      {"input_devices", facts.input_devices},
  };
  return json.dump(2);
}

}  // namespace hubrt::packaging
