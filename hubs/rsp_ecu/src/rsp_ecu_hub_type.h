// The RSP ECU hub type: nodes of type "tool_changer" (lock valve, gripper valve, tool-ID lines,
// gripper confirms, pressure switch), each watching the Dock ECU's State through a subscription.
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::rsp_ecu {
const hub_api::HubType& rsp_ecu_hub_type() noexcept;
}  // namespace hubrt::rsp_ecu
