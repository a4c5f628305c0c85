// http: REST devices (a MiR100's REST API).
#include <algorithm>

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal::board_detail {
namespace {

bool printable(std::string_view text) {
  return std::none_of(text.begin(), text.end(),
                      [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; });
}

Expected<BoardHttpDevice> parse_http_device(const std::string& name, const YamlMap& map,
                                            bool simulation_board) {
  if (!valid_identifier(name))
    return map.error("not a valid device name (lower-case letters, digits, '_' and '-')");
  if (auto ok = map.only_keys({"host", "port", "base_path", "timeout_ms", "connect_timeout_ms",
                               "max_response_kb", "authorization_file", "authorization"});
      !ok) {
    return std::move(ok).error();
  }
  BoardHttpDevice device;
  device.config.device = name;
  device.where = where(map);
  auto host = map.string("host");
  if (!host) return std::move(host).error();
  if (host->empty() || !printable(*host) || host->find_first_of(" /:") != std::string::npos) {
    return map.error_at("host", fmt::format("'{}' is not a host name or IPv4 address", *host));
  }
  device.config.host = *host;
  auto port = map.integer_or("port", 80, 0, 65535);
  if (!port) return std::move(port).error();
  if (*port == 0 && !simulation_board) {
    return map.error_at("port",
                        "port 0 (the simulator picks a free port) is only allowed on a simulation board");
  }
  device.config.port = static_cast<std::uint16_t>(*port);
  auto base = map.string_or("base_path", "/api/v2.0.0");
  if (!base) return std::move(base).error();
  if (!base->starts_with("/") || !printable(*base) || base->find(' ') != std::string::npos) {
    return map.error_at("base_path", fmt::format("'{}' is not a URL path (starts with '/')", *base));
  }
  device.config.base_path = *base;
  auto timeout = map.integer_or("timeout_ms", 1000, 10, 60'000);
  if (!timeout) return std::move(timeout).error();
  device.config.read_timeout = std::chrono::milliseconds(*timeout);
  auto connect = map.integer_or("connect_timeout_ms", 500, 10, 60'000);
  if (!connect) return std::move(connect).error();
  device.config.connect_timeout = std::chrono::milliseconds(*connect);
  auto max_kb = map.integer_or("max_response_kb", 64, 1, 4096);
  if (!max_kb) return std::move(max_kb).error();
  device.config.max_response_bytes = static_cast<std::size_t>(*max_kb) * 1024;
  if (map.has("authorization") && map.has("authorization_file")) {
    return map.error("give at most one of authorization and authorization_file");
  }
  if (map.has("authorization")) {
    // A credential in a board file is readable by anyone who reads the board: simulation only.
    if (!simulation_board) {
      return map.error_at(
          "authorization",
          "an inline authorization is only allowed on a simulation board: use authorization_file");
    }
    auto value = map.string("authorization");
    if (!value) return std::move(value).error();
    if (!printable(*value)) return map.error_at("authorization", "contains a control character");
    device.config.authorization = *value;
  }
  auto file = map.string_or("authorization_file", "");
  if (!file) return std::move(file).error();
  if (!file->empty() && !file->starts_with("/")) {
    return map.error_at("authorization_file", fmt::format("'{}' is not an absolute path", *file));
  }
  device.authorization_file = *file;
  return device;
}

}  // namespace

Expected<void> parse_http(const YamlMap& root, BoardConfig& board, bool simulation_board) {
  auto devices = root.named_maps("http");
  if (!devices) return std::move(devices).error();
  for (const auto& [name, map] : *devices) {
    auto device = parse_http_device(name, map, simulation_board);
    if (!device) return std::move(device).error();
    board.http.push_back(std::move(*device));
  }
  return {};
}

}  // namespace hubrt::hal::board_detail
