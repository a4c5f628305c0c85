// Each node type's logic as hubd builds it for the simulated station: settings from the hub
// file under hubs/, devices from the host-sim board through the scripted backend, one clock for
// the process. Fresh logic per call, so every input starts from a node that just started.
#pragma once

#include <string>

#include "hubrt/base/time.h"

#include "dock_logic.h"
#include "lift_logic.h"
#include "rsp_logic.h"
#include "smart_tool_logic.h"

namespace hubrt::fuzz {

// The clock every harness steps (manual) and every simulator runs on.
ManualClock& fuzz_clock();

// The node's name in its hub file.
const std::string& node_name(std::string_view hub, std::string_view type);

dock_ecu::DockLogic make_dock_logic();
// The Dock ECU's State never arrives: the unlock interlock refuses, as with a silent dock.
rsp_ecu::RspLogic make_rsp_logic();
// The robot holds the smart tool (so a valid tighten gets as far as the CAN frames it sends).
tool_ecu::SmartToolLogic make_smart_tool_logic();
// The drive answers as the scripted backend's Modbus script says (free-running: not at all).
tool_ecu::LiftLogic make_lift_logic();
// The same with no least time between two requests: every cycle whose request completed sends
// the next, so each answer the harness offers goes to one request.
tool_ecu::LiftLogic make_lift_logic_lockstep();

}  // namespace hubrt::fuzz
