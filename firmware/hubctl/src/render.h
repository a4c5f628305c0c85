// Human-readable rendering of a sample: YAML-like lines, the way a controls engineer reads a
// State at a glance. A State header's lifecycle shows its name too: "lifecycle: 3 (operational)".
#pragma once

#include <string>
#include <string_view>

#include <nlohmann/json.hpp>

namespace hubrt::hubctl {

// A float that is NaN (not measured: README, "The wire contract") or infinite is null in the JSON
// of a sample (msgs/json.h: JSON has no NaN); the human form prints it as NaN.
std::string render_human(const nlohmann::ordered_json& value);

// `object[key]` when it is a number, else NaN: a float field a peer sent as NaN (null in JSON),
// a missing field, or one of another type. Never throws.
double number_or_nan(const nlohmann::ordered_json& object, std::string_view key);

}  // namespace hubrt::hubctl
