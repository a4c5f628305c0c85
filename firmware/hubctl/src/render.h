// Human-readable rendering of a sample: YAML-like lines, the way a controls engineer reads a
// State at a glance. A State header's lifecycle shows its name too: "lifecycle: 3 (operational)".
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace hubrt::hubctl {

std::string render_human(const nlohmann::ordered_json& value);

}  // namespace hubrt::hubctl
