// Helpers shared by the board loader's section parsers.
#pragma once

#include <cstdint>
#include <string>
#include <string_view>

#include "hubrt/base/status.h"
#include "hubrt/config/yaml_map.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::hal::board_detail {

using config::YamlMap;

// Where a mapping starts in its file.
SourceLocation where(const YamlMap& map);
SourceLocation where(const YAML::Mark& mark);

// Logical signal names: lower-case words of [a-z0-9_] separated by dots, starting with a letter.
bool valid_signal_name(std::string_view name) noexcept;
// Names of buses, devices, chips, supplies, hubs, boards: [a-z0-9_-], starting with a letter.
bool valid_identifier(std::string_view name) noexcept;

// "input 'x' (line 9)": how messages refer to an earlier declaration.
std::string declared_at(std::string_view what, std::string_view name, SourceLocation where);

// `baud:` of a serial line (Modbus RTU, RFID readers): one of the standard rates 1200 ... 115200,
// `fallback` when absent.
Expected<std::int64_t> serial_baud(const YamlMap& map, std::int64_t fallback);

Expected<void> parse_gpio(const YamlMap& gpio, BoardConfig& board);
Expected<void> parse_can(const YamlMap& root, BoardConfig& board);
// TCP port 0 (picked by the simulator) is accepted on simulation boards only.
Expected<void> parse_modbus(const YamlMap& root, BoardConfig& board, bool simulation_board);
// http: REST devices. An inline authorization is accepted on simulation boards only.
Expected<void> parse_http(const YamlMap& root, BoardConfig& board, bool simulation_board);
Expected<void> parse_rfid(const YamlMap& root, BoardConfig& board);
Expected<void> parse_simulation(const YamlMap& simulation, BoardConfig& board);

}  // namespace hubrt::hal::board_detail
