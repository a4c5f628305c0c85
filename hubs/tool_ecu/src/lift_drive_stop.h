// The lift drive told to stop once the Tool ECU's hub process has ended (`hubd --safe-outputs`,
// the unit's ExecStopPost): one Modbus write of the control word with every bit cleared — enable
// 0 switches the power stage off at once and the lift holds on its brake
// (docs/protocols/lift-drive-modbus.md, "Holding registers": the control word bits). Best effort:
// a drive that does not answer within the timeout is left to its own communication watchdog
// (drive_watchdog_ms), which the hub wrote on every exchange and which stops it within that time
// of the hub's last request.
#pragma once

#include "hubrt/base/time.h"
#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hub_api/hub_type.h"

#include "tool_settings.h"

namespace hubrt::tool_ecu {

// Opens the lift's drive (settings.device on `board`) through `backend` with a response timeout
// of at most `timeout` and writes the stop. Never throws; the report says what happened.
hub_api::DeviceStopReport stop_lift_drive(const LiftSettings& settings, const hal::BoardConfig& board,
                                          hal::Backend& backend, Duration timeout);

}  // namespace hubrt::tool_ecu
