// The Tool ECU hub type: nodes of type "smart_tool" (the nutrunner on CAN and its run lines,
// buttons, torque-reached, summary alarm and arm position sensors) and "lift" (its lifting
// system on a Modbus drive).
#pragma once

#include "hubrt/hub_api/hub_type.h"

namespace hubrt::tool_ecu {
const hub_api::HubType& tool_ecu_hub_type() noexcept;
}  // namespace hubrt::tool_ecu
