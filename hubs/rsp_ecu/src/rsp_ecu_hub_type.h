// The RSP ECU hub type: nodes of type "tool_changer" (lock valve, gripper valve, tool-ID lines,
// gripper confirms, pressure switch), each watching the Dock ECU's State through a subscription.
#pragma once

#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hub_api/hub_type.h"

#include "rsp_logic.h"

namespace hubrt::rsp_ecu {
const hub_api::HubType& rsp_ecu_hub_type() noexcept;

// The node's devices, opened from the board now (the lock valve de-energised, the gripper valve
// at its initial level), for RspLogic::create; one that fails to open is handed over not open and
// retried by the node. Errors: a signal missing from the board (kNotFound); a lock valve the board
// would energise at start or on faults (kInvalidArgument, before anything is opened).
Expected<RspDevices> open_rsp_devices(const RspSettings& settings, const hal::BoardConfig& board,
                                      hal::Backend& backend, Time now);
}  // namespace hubrt::rsp_ecu
