// The Dock ECU hub type: nodes of type "dock", one presence sensor per slot.
#pragma once

#include <vector>

#include "hubrt/hal/backend.h"
#include "hubrt/hal/board/board_config.h"
#include "hubrt/hal/common/supervised_device.h"
#include "hubrt/hub_api/hub_type.h"

#include "dock_logic.h"

namespace hubrt::dock_ecu {
const hub_api::HubType& dock_ecu_hub_type() noexcept;

// The slots' sensors, opened from the board now (in the order of `slots`), for DockLogic::create;
// one that fails to open is handed over not open and retried by the node.
// Errors: a slot's signal missing from the board (kNotFound).
Expected<std::vector<hal::SupervisedInput>> open_slot_sensors(const std::vector<SlotConfig>& slots,
                                                              const hal::BoardConfig& board,
                                                              hal::Backend& backend, Time now);
}  // namespace hubrt::dock_ecu
