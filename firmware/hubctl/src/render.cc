#include "render.h"

#include <cmath>

#include <fmt/format.h>

#include "hubrt/runtime/lifecycle.h"

#include "sample_decoder.h"

namespace hubrt::hubctl {
namespace {

bool is_scalar(const nlohmann::ordered_json& v) {
  return !v.is_object() && !v.is_array();
}

std::string scalar(const nlohmann::ordered_json& v) {
  if (v.is_string()) {
    const auto& s = v.get_ref<const std::string&>();
    return s.empty() ? "''" : s;
  }
  if (v.is_number_float()) return fmt::format("{:g}", v.get<double>());
  if (v.is_null()) return "NaN";  // only a non-finite float is null in a sample's JSON
  return safe_dump(v);
}

// A State header's lifecycle number, with its name: "3 (operational)".
bool is_lifecycle(std::string_view parent_key, std::string_view key, const nlohmann::ordered_json& item) {
  return parent_key == "header" && key == "lifecycle" && item.is_number_unsigned();
}

void render(const nlohmann::ordered_json& value, int indent, std::string& out,
            std::string_view parent_key = {}) {
  const std::string pad(static_cast<std::size_t>(indent), ' ');
  if (value.is_object()) {
    for (const auto& [key, item] : value.items()) {
      if (is_lifecycle(parent_key, key, item)) {
        const auto number = item.get<std::uint64_t>();
        const std::string_view name =
            number <= 255 ? runtime::lifecycle_name(static_cast<std::uint8_t>(number)) : "unknown";
        out += fmt::format("{}{}: {} ({})\n", pad, key, number, name);
      } else if (is_scalar(item)) {
        out += fmt::format("{}{}: {}\n", pad, key, scalar(item));
      } else if (item.empty()) {
        out += fmt::format("{}{}: {}\n", pad, key, item.is_array() ? "[]" : "{}");
      } else if (item.is_array() && std::all_of(item.begin(), item.end(), is_scalar)) {
        std::string joined;
        for (const auto& element : item) joined += (joined.empty() ? "" : ", ") + scalar(element);
        out += fmt::format("{}{}: [{}]\n", pad, key, joined);
      } else {
        out += fmt::format("{}{}:\n", pad, key);
        render(item, indent + 2, out, key);
      }
    }
  } else if (value.is_array()) {
    for (const auto& item : value) {
      if (is_scalar(item)) {
        out += fmt::format("{}- {}\n", pad, scalar(item));
      } else {
        std::string inner;
        render(item, indent + 2, inner);
        inner.replace(static_cast<std::size_t>(indent), 2, "- ");
        out += inner;
      }
    }
  } else {
    out += fmt::format("{}{}\n", pad, scalar(value));
  }
}

}  // namespace

std::string render_human(const nlohmann::ordered_json& value) {
  std::string out;
  render(value, 0, out);
  return out;
}

double number_or_nan(const nlohmann::ordered_json& object, std::string_view key) {
  if (!object.is_object()) return std::nan("");
  const auto it = object.find(std::string(key));
  return it != object.end() && it->is_number() ? it->get<double>() : std::nan("");
}

}  // namespace hubrt::hubctl
