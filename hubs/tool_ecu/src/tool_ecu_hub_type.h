// The Tool ECU hub type: nodes of type "smart_tool" (the nutrunner on CAN and its run lines,
// buttons, torque-reached, summary alarm and arm position sensors) and "lift" (its lifting
// system on a Modbus drive).
#pragma once

#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hub_api/hub_type.h"

#include "smart_tool_logic.h"

namespace hubrt::tool_ecu {
const hub_api::HubType& tool_ecu_hub_type() noexcept;

// The smart tool node's devices, opened from the board now (run lines at their initial level, the
// CAN bus filtered for the controller), for SmartToolLogic::create; one that fails to open is
// handed over not open and retried by the node. Errors: a signal or the bus missing from the board
// (kNotFound).
Expected<SmartToolDevices> open_smart_tool_devices(const SmartToolSettings& settings,
                                                   const hal::BoardConfig& board, hal::Backend& backend,
                                                   Time now);
}  // namespace hubrt::tool_ecu
