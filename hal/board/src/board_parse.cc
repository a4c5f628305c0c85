#include "board_parse.h"

#include <algorithm>
#include <array>

#include <fmt/format.h>

namespace hubrt::hal::board_detail {
namespace {

bool lower_or_digit(char c) noexcept {
  return (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9');
}

}  // namespace

SourceLocation where(const YAML::Mark& mark) {
  if (mark.is_null()) return {};
  return SourceLocation{mark.line + 1, mark.column + 1};
}

SourceLocation where(const YamlMap& map) {
  return where(map.node().Mark());
}

bool valid_signal_name(std::string_view name) noexcept {
  if (name.empty() || name.front() < 'a' || name.front() > 'z' || name.back() == '.') return false;
  char previous = ' ';
  for (const char c : name) {
    if (c == '.' && previous == '.') return false;
    if (c != '.' && c != '_' && !lower_or_digit(c)) return false;
    previous = c;
  }
  return true;
}

bool valid_identifier(std::string_view name) noexcept {
  if (name.empty() || name.front() < 'a' || name.front() > 'z') return false;
  return std::all_of(name.begin(), name.end(),
                     [](char c) { return lower_or_digit(c) || c == '_' || c == '-'; });
}

std::string declared_at(std::string_view what, std::string_view name, SourceLocation where) {
  return fmt::format("{} '{}' (line {})", what, name, where.line);
}

Expected<std::int64_t> serial_baud(const YamlMap& map, std::int64_t fallback) {
  static constexpr std::array<std::int64_t, 8> kRates = {1200, 2400, 4800, 9600, 19200, 38400, 57600, 115200};
  auto baud = map.integer_or("baud", fallback, kRates.front(), kRates.back());
  if (!baud) return std::move(baud).error();
  if (std::find(kRates.begin(), kRates.end(), *baud) == kRates.end()) {
    return map.error_at("baud", fmt::format("{} is not a standard baud rate (1200 ... 115200)", *baud));
  }
  return baud;
}

}  // namespace hubrt::hal::board_detail
