// The Dock ECU hub type: nodes of type "dock", one presence sensor per slot.
#pragma once

#include "hubrt/assembly/hub_type.h"

namespace hubrt::dock_ecu {
const assembly::HubType& dock_ecu_hub_type() noexcept;
}  // namespace hubrt::dock_ecu
