#include "hubrt/packaging/wiring_tables.h"

#include <algorithm>
#include <array>
#include <chrono>
#include <tuple>
#include <variant>

#include <fmt/format.h>

namespace hubrt::packaging {
namespace {

// Header pin of BCM GPIO 0..27, the lines the 40-pin header carries on every Pi since the B+.
constexpr std::array<int, 28> kHeaderPinOfBcm = {27, 28, 3,  5,  7,  29, 31, 26, 24, 21, 19, 23, 32, 33,
                                                 8,  10, 36, 11, 12, 35, 38, 40, 15, 16, 18, 22, 37, 13};

bool is_rpi_gpio_chip(std::string_view label) {
  return label == "pinctrl-bcm2835" || label == "pinctrl-bcm2711" || label == "pinctrl-rp1";
}

std::string milliseconds(Duration d) {
  return fmt::format("{} ms", std::chrono::duration_cast<std::chrono::milliseconds>(d).count());
}

const char* level(bool active) {
  return active ? "active" : "inactive";
}

const char* bias_text(hal::Bias bias) {
  switch (bias) {
    case hal::Bias::kDisabled:
      return "disabled";
    case hal::Bias::kPullUp:
      return "pull-up";
    case hal::Bias::kPullDown:
      return "pull-down";
    case hal::Bias::kAsIs:
      break;
  }
  return "as is";
}

// One GPIO line of the board, input or output, as a table row.
struct GpioRow {
  std::string chip_alias;
  unsigned line = 0;
  std::string cells;  // everything after the "GPIO" column
};

std::string gpio_table(const hal::BoardConfig& board) {
  std::vector<GpioRow> rows;
  for (const hal::BoardInput& input : board.inputs) {
    const hal::DigitalInputConfig& c = input.config;
    std::string notes;
    if (c.debounce.count() > 0) notes = "debounce " + milliseconds(c.debounce);
    if (c.catch_pulses) notes = "short pulses caught";
    rows.push_back({input.chip_alias, c.line,
                    fmt::format("`{}` | input | {} | {} | {} |", c.signal,
                                c.polarity == hal::Polarity::kActiveLow ? "low" : "high", bias_text(c.bias),
                                notes.empty() ? "—" : notes)});
  }
  for (const hal::BoardOutput& output : board.outputs) {
    const hal::DigitalOutputConfig& c = output.config;
    rows.push_back({output.chip_alias, c.line,
                    fmt::format("`{}` | output | {} | — | starts {}; safe: {} |", c.signal,
                                c.polarity == hal::Polarity::kActiveLow ? "low" : "high", level(c.initial),
                                level(c.safe))});
  }
  std::sort(rows.begin(), rows.end(), [](const GpioRow& a, const GpioRow& b) {
    return std::tie(a.chip_alias, a.line) < std::tie(b.chip_alias, b.line);
  });

  std::string out;
  for (const hal::BoardGpioChip& chip : board.chips) {
    out += fmt::format("GPIO chip `{}`: {} `{}`.\n", chip.alias,
                       chip.kind == hal::GpioChipSelectorKind::kLabel  ? "label"
                       : chip.kind == hal::GpioChipSelectorKind::kName ? "kernel name"
                                                                       : "device",
                       chip.selector);
  }
  out += "\n| header pin | GPIO | signal | direction | active | bias | notes |\n";
  out += "|---|---|---|---|---|---|---|\n";
  for (const GpioRow& row : rows) {
    const hal::BoardGpioChip* chip = board.find_chip(row.chip_alias);
    const bool rpi_chip = chip != nullptr && chip->kind == hal::GpioChipSelectorKind::kLabel &&
                          is_rpi_gpio_chip(chip->selector);
    const auto pin = rpi_chip ? rpi_header_pin(chip->selector, row.line) : std::nullopt;
    out += fmt::format(
        "| {} | {} | {}\n", pin ? std::to_string(*pin) : "—",
        rpi_chip ? fmt::format("BCM {}", row.line) : fmt::format("`{}` line {}", row.chip_alias, row.line),
        row.cells);
  }
  return out;
}

std::string can_table(const hal::BoardConfig& board) {
  std::string out = "| CAN bus | interface | bitrate |\n|---|---|---|\n";
  for (const hal::BoardCanBus& can : board.can) {
    out += fmt::format("| `{}` | `{}` | {} kbit/s |\n", can.config.bus, can.config.interface,
                       can.config.bitrate / 1000.0);
  }
  return out;
}

std::string modbus_table(const hal::BoardConfig& board) {
  std::string out = "| Modbus device | connection | unit | response timeout |\n|---|---|---|---|\n";
  for (const hal::BoardModbusDevice& device : board.modbus) {
    const hal::ModbusConfig& c = device.config;
    std::string connection;
    if (const auto* tcp = std::get_if<hal::ModbusTcpEndpoint>(&c.endpoint)) {
      connection = fmt::format("TCP {}:{}", tcp->host, tcp->port);
    } else {
      const auto& rtu = std::get<hal::ModbusRtuEndpoint>(c.endpoint);
      connection = fmt::format("RTU `{}`, {} baud, {}{}{}", rtu.device, rtu.baud, rtu.data_bits, rtu.parity,
                               rtu.stop_bits);
    }
    out += fmt::format("| `{}` | {} | {} | {} |\n", c.device, connection, c.unit_id,
                       milliseconds(c.response_timeout));
  }
  return out;
}

std::string http_table(const hal::BoardConfig& board) {
  std::string out = "| HTTP device | endpoint | timeouts | authorization |\n|---|---|---|---|\n";
  for (const hal::BoardHttpDevice& device : board.http) {
    const hal::HttpConfig& c = device.config;
    out += fmt::format("| `{}` | `http://{}:{}{}` | connect {}, read {} | {} |\n", c.device, c.host, c.port,
                       c.base_path, milliseconds(c.connect_timeout), milliseconds(c.read_timeout),
                       device.authorization_file.empty() ? std::string("none")
                                                         : fmt::format("`{}`", device.authorization_file));
  }
  return out;
}

}  // namespace

std::optional<int> rpi_header_pin(std::string_view chip_label, unsigned line) {
  if (!is_rpi_gpio_chip(chip_label) || line >= kHeaderPinOfBcm.size()) return std::nullopt;
  return kHeaderPinOfBcm.at(line);
}

std::string wiring_tables(const hal::BoardConfig& board) {
  std::string out = fmt::format("### {}\n\n", board.name);
  if (!board.description.empty()) out += fmt::format("{}. ", board.description);
  out += fmt::format("Architecture `{}`, hub `{}`.\n\n", board.arch, fmt::join(board.hubs, "`, `"));
  if (!board.chips.empty()) out += gpio_table(board) + "\n";
  if (!board.can.empty()) out += can_table(board) + "\n";
  if (!board.modbus.empty()) out += modbus_table(board) + "\n";
  if (!board.http.empty()) out += http_table(board) + "\n";
  out.pop_back();  // one newline at the end, not a blank line
  return out;
}

std::string wiring_section(std::vector<hal::BoardConfig> boards) {
  std::erase_if(boards, [](const hal::BoardConfig& board) { return board.simulation.has_value(); });
  std::sort(boards.begin(), boards.end(),
            [](const hal::BoardConfig& a, const hal::BoardConfig& b) { return a.name < b.name; });
  std::string out;
  for (const hal::BoardConfig& board : boards) {
    if (!out.empty()) out += "\n";
    out += wiring_tables(board);
  }
  return out;
}

Expected<std::string> replace_generated_section(std::string_view document, std::string_view generated) {
  // Each marker must be a whole line: find "\n<marker>\n" (the document may start with it).
  const auto find_line = [document](std::string_view marker) -> std::vector<std::size_t> {
    std::vector<std::size_t> at;
    for (std::size_t pos = document.find(marker); pos != std::string_view::npos;
         pos = document.find(marker, pos + 1)) {
      const bool line_start = pos == 0 || document[pos - 1] == '\n';
      const std::size_t end = pos + marker.size();
      const bool line_end = end == document.size() || document[end] == '\n';
      if (line_start && line_end) at.push_back(pos);
    }
    return at;
  };
  const auto begin = find_line(kBeginMarker);
  const auto end = find_line(kEndMarker);
  if (begin.size() != 1 || end.size() != 1 || end.front() < begin.front()) {
    return make_error(
        ErrorCode::kInvalidArgument,
        fmt::format("expected the line '{}' once, followed later by the line '{}' once; found {} "
                    "and {}",
                    kBeginMarker, kEndMarker, begin.size(), end.size()));
  }
  std::string out(document.substr(0, begin.front() + kBeginMarker.size()));
  out += "\n\n";
  out += generated;
  if (!generated.empty() && generated.back() != '\n') out += '\n';
  out += '\n';
  out += document.substr(end.front());
  return out;
}

}  // namespace hubrt::packaging
