#include "hubrt/hal/board/board_loader.h"

#include <fmt/format.h>

#include "board_parse.h"

namespace hubrt::hal {
namespace {

using board_detail::YamlMap;

Expected<std::vector<std::string>> parse_hubs(const YamlMap& root) {
  std::vector<std::string> hubs;
  const YAML::Node hub_node = root.node()["hub"];
  if (hub_node.IsDefined() && hub_node.IsSequence()) {
    auto list = root.list_of_strings("hub");
    if (!list) return std::move(list).error();
    hubs = std::move(*list);
    if (hubs.empty()) return root.error_at("hub", "name at least one hub type");
  } else {
    auto hub = root.string("hub");
    if (!hub) return std::move(hub).error();
    hubs.push_back(std::move(*hub));
  }
  for (const std::string& hub : hubs) {
    if (!board_detail::valid_identifier(hub)) {
      return root.error_at(
          "hub", fmt::format("'{}' is not a valid hub type (lower-case letters, digits, '_', '-')", hub));
    }
  }
  return hubs;
}

Expected<BoardConfig> parse_checked_board(const YamlMap& root) {
  if (auto ok = root.only_keys(
          {"board", "description", "arch", "hub", "gpio", "can", "modbus", "http", "rfid", "simulation"});
      !ok) {
    return std::move(ok).error();
  }
  BoardConfig board;
  board.file = root.file();
  auto name = root.string("board");
  if (!name) return std::move(name).error();
  if (!board_detail::valid_identifier(*name)) {
    return root.error_at(
        "board", fmt::format("'{}' is not a valid board name (lower-case letters, digits, '_', '-')", *name));
  }
  board.name = std::move(*name);
  auto description = root.string_or("description", "");
  if (!description) return std::move(description).error();
  board.description = std::move(*description);
  auto arch = root.choice("arch", {"arm64", "armhf", "x86_64"});
  if (!arch) return std::move(arch).error();
  board.arch = std::move(*arch);
  auto hubs = parse_hubs(root);
  if (!hubs) return std::move(hubs).error();
  board.hubs = std::move(*hubs);

  if (!root.has("gpio") && !root.has("can") && !root.has("modbus") && !root.has("http") &&
      !root.has("rfid")) {
    return root.error("the board declares no devices: give at least one of gpio, can, modbus, http, rfid");
  }
  if (root.has("gpio")) {
    auto gpio = root.map("gpio");
    if (!gpio) return std::move(gpio).error();
    if (auto ok = board_detail::parse_gpio(*gpio, board); !ok) return std::move(ok).error();
  }
  if (root.has("can")) {
    if (auto ok = board_detail::parse_can(root, board); !ok) return std::move(ok).error();
  }
  if (root.has("rfid")) {
    if (auto ok = board_detail::parse_rfid(root, board); !ok) return std::move(ok).error();
  }
  const bool simulation_board = root.has("simulation");
  if (root.has("modbus")) {
    if (auto ok = board_detail::parse_modbus(root, board, simulation_board); !ok)
      return std::move(ok).error();
  }
  if (root.has("http")) {
    if (auto ok = board_detail::parse_http(root, board, simulation_board); !ok) return std::move(ok).error();
  }
  if (simulation_board) {
    auto simulation = root.map("simulation");
    if (!simulation) return std::move(simulation).error();
    if (auto ok = board_detail::parse_simulation(*simulation, board); !ok) return std::move(ok).error();
  }
  return board;
}

// yaml-cpp throws on shapes YamlMap does not expect (a mapping used as a key, say): no exception
// leaves the loader.
Expected<BoardConfig> parse_board(const YamlMap& root) {
  try {
    return parse_checked_board(root);
  } catch (const YAML::Exception& e) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("{}:{}:{}: unexpected YAML structure ({}): keys must be plain names, values "
                    "as boards/README.md describes",
                    root.file(), e.mark.line + 1, e.mark.column + 1, e.msg));
  }
}

}  // namespace

Expected<BoardConfig> load_board(const std::string& path) {
  auto root = config::YamlMap::load_file(path);
  if (!root) return std::move(root).error();
  return parse_board(*root);
}

Expected<BoardConfig> load_board_string(const std::string& text, const std::string& name) {
  auto root = config::YamlMap::load_string(text, name);
  if (!root) return std::move(root).error();
  return parse_board(*root);
}

}  // namespace hubrt::hal
