// Human-readable rendering of a sample: YAML-like lines, the way a controls engineer reads a
// State at a glance.
#pragma once

#include <string>

#include <nlohmann/json.hpp>

namespace hubrt::hubctl {

std::string render_human(const nlohmann::ordered_json& value);

}  // namespace hubrt::hubctl
