// The Dock ECU hub type: nodes of type "dock", one presence sensor per slot.
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::dock_ecu {
const hub_api::HubType& dock_ecu_hub_type() noexcept;
}  // namespace hubrt::dock_ecu
