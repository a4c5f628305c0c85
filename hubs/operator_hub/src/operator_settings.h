// The operator panel node's settings (README.md, "Settings"), read from its YAML map.
#pragma once

#include <string>

#include "hubrt/base/status.h"
#include "hubrt/config/hub_config.h"
#include "hubrt/hal/board/board_requirements.h"

namespace hubrt::operator_hub {

struct OperatorSettings {
  std::string reader;          // board RFID reader (rfid:)
  std::string confirm_button;  // board input; empty: no button
  std::string screen_confirm;  // subscription name of the screen's confirm topic; empty: none
  std::string allow_list;      // path, resolved against the hub file's folder when relative
};

// Errors name file:line: unknown keys, missing reader/allow_list, wrong types.
Expected<OperatorSettings> parse_operator_settings(const config::NodeConfig& node,
                                                   const std::string& hub_file);

void add_requirements(const OperatorSettings& settings, hal::BoardRequirements& requirements);

}  // namespace hubrt::operator_hub
