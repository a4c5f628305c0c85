// rfid: RFID badge readers, each either a Linux input device (keyboard wedge) or a serial port.

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal::board_detail {
namespace {

Expected<std::string> device_path(const YamlMap& map, std::string_view prefix, std::string_view what) {
  auto device = map.string("device");
  if (!device) return std::move(device).error();
  if (!device->starts_with(prefix) || device->find("..") != std::string::npos) {
    return map.error_at("device", fmt::format("'{}' is not {} ({}...)", *device, what, prefix));
  }
  return device;
}

Expected<void> parse_evdev(const YamlMap& map, BadgeReaderConfig& config) {
  if (auto ok = map.only_keys({"device", "grab"}); !ok) return std::move(ok).error();
  auto device = device_path(map, "/dev/input/", "an input device path");
  if (!device) return std::move(device).error();
  auto grab = map.boolean_or("grab", true);
  if (!grab) return std::move(grab).error();
  config.kind = BadgeReaderKind::kEvdev;
  config.device = std::move(*device);
  config.grab = *grab;
  return {};
}

Expected<void> parse_serial(const YamlMap& map, BadgeReaderConfig& config) {
  if (auto ok = map.only_keys({"device", "baud", "terminator"}); !ok) return std::move(ok).error();
  auto device = device_path(map, "/dev/", "a serial device path");
  if (!device) return std::move(device).error();
  auto baud = serial_baud(map, 9600);
  if (!baud) return std::move(baud).error();
  auto terminator = map.choice_or("terminator", "cr", {"cr", "lf"});
  if (!terminator) return std::move(terminator).error();
  config.kind = BadgeReaderKind::kSerial;
  config.device = std::move(*device);
  config.baud = static_cast<std::uint32_t>(*baud);
  config.terminator = *terminator == "cr" ? '\r' : '\n';
  return {};
}

Expected<BoardBadgeReader> parse_reader(const std::string& name, const YamlMap& map) {
  if (!valid_identifier(name))
    return map.error("not a valid reader name (lower-case letters, digits, '_' and '-')");
  if (auto ok = map.only_keys({"evdev", "serial", "timeout_ms"}); !ok) return std::move(ok).error();
  if (map.has("evdev") == map.has("serial")) return map.error("give exactly one of evdev or serial");
  BoardBadgeReader reader;
  reader.config.reader = name;
  reader.where = where(map);
  const bool evdev = map.has("evdev");
  auto kind_map = map.map(evdev ? "evdev" : "serial");
  if (!kind_map) return std::move(kind_map).error();
  auto parsed = evdev ? parse_evdev(*kind_map, reader.config) : parse_serial(*kind_map, reader.config);
  if (!parsed) return std::move(parsed).error();
  auto timeout = map.integer_or("timeout_ms", 500, 10, 10'000);
  if (!timeout) return std::move(timeout).error();
  reader.config.timeout = std::chrono::milliseconds(*timeout);
  return reader;
}

}  // namespace

Expected<void> parse_rfid(const YamlMap& root, BoardConfig& board) {
  auto readers = root.named_maps("rfid");
  if (!readers) return std::move(readers).error();
  for (const auto& [name, map] : *readers) {
    auto reader = parse_reader(name, map);
    if (!reader) return std::move(reader).error();
    board.badge_readers.push_back(std::move(*reader));
  }
  return {};
}

}  // namespace hubrt::hal::board_detail
