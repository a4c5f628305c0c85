// can: and modbus:.
#include <algorithm>

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal::board_detail {
namespace {

constexpr std::int64_t kMaxStandardId = 0x7FF;
constexpr std::int64_t kMaxExtendedId = 0x1FFF'FFFF;
constexpr std::size_t kMaxInterfaceName = 15;  // IFNAMSIZ - 1

bool valid_interface(std::string_view name) noexcept {
  return !name.empty() && name.size() <= kMaxInterfaceName &&
         std::all_of(name.begin(), name.end(), [](char c) {
           return (c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') || c == '-' ||
                  c == '_' || c == '.';
         });
}

Expected<CanFilter> parse_filter(const YamlMap& map) {
  if (auto ok = map.only_keys({"id", "mask", "extended"}); !ok) return std::move(ok).error();
  CanFilter filter;
  auto extended = map.boolean_or("extended", false);
  if (!extended) return std::move(extended).error();
  filter.extended = *extended;
  const std::int64_t max = filter.extended ? kMaxExtendedId : kMaxStandardId;
  auto id = map.integer("id", 0, max);
  if (!id) return std::move(id).error();
  auto mask = map.integer_or("mask", max, 0, max);
  if (!mask) return std::move(mask).error();
  filter.id = static_cast<std::uint32_t>(*id);
  filter.mask = static_cast<std::uint32_t>(*mask);
  return filter;
}

Expected<BoardCanBus> parse_can_bus(const std::string& name, const YamlMap& map) {
  if (!valid_identifier(name))
    return map.error("not a valid bus name (lower-case letters, digits, '_' and '-')");
  if (auto ok = map.only_keys({"interface", "bitrate", "filters"}); !ok) return std::move(ok).error();
  BoardCanBus bus;
  bus.config.bus = name;
  bus.where = where(map);
  auto interface = map.string("interface");
  if (!interface) return std::move(interface).error();
  if (!valid_interface(*interface)) {
    return map.error_at("interface",
                        fmt::format("'{}' is not a network interface name (1 to 15 of letters, digits, "
                                    "'-', '_', '.')",
                                    *interface));
  }
  bus.config.interface = *interface;
  auto bitrate = map.integer_or("bitrate", 500'000, 10'000, 1'000'000);
  if (!bitrate) return std::move(bitrate).error();
  bus.config.bitrate = static_cast<std::uint32_t>(*bitrate);
  auto filters = map.list_of_maps("filters", /*optional=*/true);
  if (!filters) return std::move(filters).error();
  for (const YamlMap& filter_map : *filters) {
    auto filter = parse_filter(filter_map);
    if (!filter) return std::move(filter).error();
    bus.config.filters.push_back(*filter);
  }
  return bus;
}

Expected<ModbusTcpEndpoint> parse_tcp(const YamlMap& map, bool simulation_board) {
  if (auto ok = map.only_keys({"host", "port"}); !ok) return std::move(ok).error();
  ModbusTcpEndpoint tcp;
  auto host = map.string("host");
  if (!host) return std::move(host).error();
  auto port = map.integer_or("port", 502, 0, 65535);
  if (!port) return std::move(port).error();
  if (*port == 0 && !simulation_board) {
    return map.error_at("port",
                        "port 0 (the simulator picks a free port) is only allowed on a simulation board");
  }
  tcp.host = *host;
  tcp.port = static_cast<std::uint16_t>(*port);
  return tcp;
}

Expected<ModbusRtuEndpoint> parse_rtu(const YamlMap& map) {
  if (auto ok = map.only_keys({"device", "baud", "parity", "data_bits", "stop_bits"}); !ok) {
    return std::move(ok).error();
  }
  ModbusRtuEndpoint rtu;
  auto device = map.string("device");
  if (!device) return std::move(device).error();
  if (!device->starts_with("/dev/")) {
    return map.error_at("device", fmt::format("'{}' is not a serial device path (/dev/...)", *device));
  }
  auto baud = serial_baud(map, 19200);
  if (!baud) return std::move(baud).error();
  auto parity = map.choice_or("parity", "E", {"N", "E", "O"});
  if (!parity) return std::move(parity).error();
  auto data_bits = map.integer_or("data_bits", 8, 5, 8);
  if (!data_bits) return std::move(data_bits).error();
  auto stop_bits = map.integer_or("stop_bits", 1, 1, 2);
  if (!stop_bits) return std::move(stop_bits).error();
  rtu.device = *device;
  rtu.baud = static_cast<std::uint32_t>(*baud);
  rtu.parity = parity->front();
  rtu.data_bits = static_cast<int>(*data_bits);
  rtu.stop_bits = static_cast<int>(*stop_bits);
  return rtu;
}

Expected<BoardModbusDevice> parse_modbus_device(const std::string& name, const YamlMap& map,
                                                bool simulation_board) {
  if (!valid_identifier(name))
    return map.error("not a valid device name (lower-case letters, digits, '_' and '-')");
  if (auto ok = map.only_keys({"tcp", "rtu", "unit", "timeout_ms", "reconnect_ms"}); !ok) {
    return std::move(ok).error();
  }
  if (map.has("tcp") == map.has("rtu")) return map.error("give exactly one of tcp or rtu");
  BoardModbusDevice device;
  device.config.device = name;
  device.where = where(map);
  const bool tcp = map.has("tcp");
  auto endpoint_map = map.map(tcp ? "tcp" : "rtu");
  if (!endpoint_map) return std::move(endpoint_map).error();
  if (tcp) {
    auto endpoint = parse_tcp(*endpoint_map, simulation_board);
    if (!endpoint) return std::move(endpoint).error();
    device.config.endpoint = *endpoint;
  } else {
    auto endpoint = parse_rtu(*endpoint_map);
    if (!endpoint) return std::move(endpoint).error();
    device.config.endpoint = *endpoint;
  }
  // Modbus/TCP gateways may use any unit id; on a serial line 0 is broadcast and 248+ reserved.
  auto unit = tcp ? map.integer_or("unit", 1, 0, 255) : map.integer_or("unit", 1, 1, 247);
  if (!unit) return std::move(unit).error();
  device.config.unit_id = static_cast<std::uint8_t>(*unit);
  auto timeout = map.integer_or("timeout_ms", 100, 1, 60'000);
  if (!timeout) return std::move(timeout).error();
  device.config.response_timeout = std::chrono::milliseconds(*timeout);
  auto reconnect = map.integer_or("reconnect_ms", 500, 0, 600'000);
  if (!reconnect) return std::move(reconnect).error();
  device.config.reconnect_interval = std::chrono::milliseconds(*reconnect);
  return device;
}

}  // namespace

Expected<void> parse_can(const YamlMap& root, BoardConfig& board) {
  auto buses = root.named_maps("can");
  if (!buses) return std::move(buses).error();
  for (const auto& [name, map] : *buses) {
    auto bus = parse_can_bus(name, map);
    if (!bus) return std::move(bus).error();
    board.can.push_back(std::move(*bus));
  }
  return {};
}

Expected<void> parse_modbus(const YamlMap& root, BoardConfig& board, bool simulation_board) {
  auto devices = root.named_maps("modbus");
  if (!devices) return std::move(devices).error();
  for (const auto& [name, map] : *devices) {
    auto device = parse_modbus_device(name, map, simulation_board);
    if (!device) return std::move(device).error();
    board.modbus.push_back(std::move(*device));
  }
  return {};
}

}  // namespace hubrt::hal::board_detail
