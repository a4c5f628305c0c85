// What a hub type needs from a board, and the check that the board provides it.
#pragma once

#include <string>
#include <vector>

#include "hubrt/base/status.h"
#include "hubrt/hal/board/board_config.h"

namespace hubrt::hal {

struct BoardRequirements {
  std::string hub;                          // hub type, e.g. "dock_ecu"
  std::vector<std::string> inputs;          // logical input signals
  std::vector<std::string> outputs;         // logical output signals
  std::vector<std::string> can_buses;       // CAN bus names
  std::vector<std::string> modbus_devices;  // Modbus device names
  std::vector<std::string> http_devices{};  // HTTP (REST) device names
  // RFID reader names (rfid:). Initialised so that requirement lists written before it still compile.
  std::vector<std::string> badge_readers{};
};

// Checks that `board` is wired for `required.hub` and declares every required signal, bus and
// device as the right kind. The first problem is returned as kFailedPrecondition with a message
// that names the board file and, where the name exists as another kind, its line, e.g.
//   "hub dock_ecu needs input 'dock.slot.filter_tool' but boards/x.yaml declares it as an output
//    (line 12)". Thread-safe (no shared state).
Expected<void> check_requirements(const BoardConfig& board, const BoardRequirements& required);

}  // namespace hubrt::hal
