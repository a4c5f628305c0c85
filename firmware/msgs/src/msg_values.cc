#include "msg_values.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <limits>
#include <system_error>

#include <fmt/format.h>

namespace hubrt::msgs::ros {
namespace {

std::string lower(std::string_view s) {
  std::string out(s);
  for (char& c : out) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return out;
}

// Python's int(text) or int(text, 0), as rosidl tries them: an optional sign, then decimal digits
// or a 0x / 0o / 0b prefix and its digits. False when the text is none of these or does not fit
// 64 bits.
bool parse_integer(std::string_view text, bool& negative, std::uint64_t& magnitude) {
  negative = false;
  if (!text.empty() && (text.front() == '-' || text.front() == '+')) {
    negative = text.front() == '-';
    text.remove_prefix(1);
  }
  int base = 10;
  if (text.size() > 2 && text[0] == '0') {
    const char prefix = static_cast<char>(std::tolower(static_cast<unsigned char>(text[1])));
    if (prefix == 'x') base = 16;
    if (prefix == 'o') base = 8;
    if (prefix == 'b') base = 2;
    if (base != 10) text.remove_prefix(2);
  }
  if (text.empty()) return false;
  const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), magnitude, base);
  return ec == std::errc() && end == text.data() + text.size();
}

std::string check_integer(std::string_view type, std::string_view text, std::string& out) {
  const bool is_unsigned = type.starts_with("u") || type == "byte" || type == "char";
  int bits = 8;
  if (type != "byte" && type != "char") {
    const std::string_view digits = type.substr(is_unsigned ? 4 : 3);
    std::from_chars(digits.data(), digits.data() + digits.size(), bits);
  }
  // The range as rosidl states it: [0, 2^bits - 1] or [-2^(bits-1), 2^(bits-1) - 1].
  const std::uint64_t upper =
      is_unsigned ? (bits == 64 ? std::numeric_limits<std::uint64_t>::max() : (std::uint64_t{1} << bits) - 1)
                  : (std::uint64_t{1} << (bits - 1)) - 1;
  const std::uint64_t lowest_magnitude = is_unsigned ? 0 : std::uint64_t{1} << (bits - 1);
  const std::string range =
      is_unsigned ? fmt::format("must be a valid integer value >= 0 and <= {}", upper)
                  : fmt::format("must be a valid integer value >= -{} and <= {}", lowest_magnitude, upper);
  bool negative = false;
  std::uint64_t magnitude = 0;
  if (!parse_integer(text, negative, magnitude)) return range;
  if (negative && magnitude != 0) {
    if (magnitude > lowest_magnitude) return range;
    out = fmt::format("-{}", magnitude);
    return {};
  }
  if (magnitude > upper) return range;
  out = fmt::format("{}", magnitude);
  return {};
}

std::string check_float(std::string_view type, std::string_view text, std::string& out) {
  const std::string problem = "must be a finite floating point number using '.' as the separator";
  std::string_view digits = text;
  if (digits.starts_with("+")) digits.remove_prefix(1);
  double value = 0;
  const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), value);
  if (digits.empty() || ec != std::errc() || end != digits.data() + digits.size() || !std::isfinite(value)) {
    return problem;
  }
  if (type == "float32" && std::fabs(value) > std::numeric_limits<float>::max()) {
    return "must be within float32's range";
  }
  // The shortest text that reads back as the same double, always with a '.' or an exponent so
  // that IDL reads a floating-point literal.
  out = fmt::format("{}", value);
  if (out.find_first_of(".e") == std::string::npos) out += ".0";
  return {};
}

std::string check_string(std::string_view text, std::string& out) {
  for (const char quote : {'"', '\''}) {
    if (text.size() < 2 || text.front() != quote || text.back() != quote) continue;
    const std::string_view inner = text.substr(1, text.size() - 2);
    out.clear();
    for (std::size_t i = 0; i < inner.size(); ++i) {
      if (inner[i] == quote) {
        if (i == 0 || inner[i - 1] != '\\') return "string inner quotes not properly escaped";
        out.back() = quote;  // the backslash before it goes
        continue;
      }
      out += inner[i];
    }
    return {};
  }
  out = std::string(text);
  return {};
}

}  // namespace

std::string normalise_constant_value(std::string_view type, std::string_view text, std::string& out) {
  if (type == "bool") {
    const std::string value = lower(text);
    if (value == "true" || value == "1") {
      out = "true";
    } else if (value == "false" || value == "0") {
      out = "false";
    } else {
      return "must be either 'true' / '1' or 'false' / '0'";
    }
    return {};
  }
  if (type == "float32" || type == "float64") return check_float(type, text, out);
  if (type == "string" || type == "wstring") return check_string(text, out);
  return check_integer(type, text, out);
}

}  // namespace hubrt::msgs::ros
