// The tool changer's one safety rule: it opens only when the tool on it is home in its dock. A
// dropped end-effector is the worst failure of the cell, so everything that is not a positive
// confirmation from a fresh Dock ECU State counts as "not allowed".
#pragma once

#include <string_view>

#include "hubrt/hub_api/remote_state.h"
#include "hubrt/runtime/message_ops.h"

#include "dock_reflect.h"  // the Dock ECU's messages (its library is not ours to link)
#include "dock_typed.h"
#include "tool_id.h"

namespace hubrt::rsp_ecu {

// Whether the changer may open at `now`, given the tool on it and the Dock ECU's State:
//   - tool undefined                      -> not allowed (which tool would fall is unknown)
//   - no fresh Dock ECU State (never received, or older than the subscription's timeout)
//                                         -> not allowed
//   - one tool, its slot reported occupied -> allowed
//   - one tool, slot empty or not listed  -> not allowed
//   - no tool, fresh Dock ECU State       -> allowed (nothing to drop; the changer must be open
//                                            to take a tool)
// `tool_name` is the name of the tool `tool` identifies (ignored unless tool.is_one()). On "not
// allowed" `why` says why in a sentence fit for error_list, worded so that it does not change
// from cycle to cycle while the reason stays the same (the log is not flooded); on "allowed" it
// is cleared. Deterministic in its arguments; never allocates.
[[nodiscard]] bool unlock_permitted(const ToolId& tool, std::string_view tool_name,
                                    const hub_api::RemoteState<hub_msgs::DockStateView>& dock, Time now,
                                    runtime::Problem& why) noexcept;

}  // namespace hubrt::rsp_ecu
