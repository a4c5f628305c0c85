#include "unlock_interlock.h"

namespace hubrt::rsp_ecu {
namespace {

// The slot of `tool` in the Dock ECU State, or null when the dock does not list it.
const hub_msgs_msg_dds__DockSlot_* find_slot(const dock_ecu::DockState& dock,
                                             std::string_view tool) noexcept {
  if (dock.slots._buffer == nullptr) return nullptr;
  for (std::uint32_t i = 0; i < dock.slots._length; ++i) {
    const auto& slot = dock.slots._buffer[i];
    if (slot.name != nullptr && std::string_view(slot.name) == tool) return &slot;
  }
  return nullptr;
}

}  // namespace

bool unlock_permitted(const ToolId& tool, std::string_view tool_name,
                      const hub_api::RemoteState<dock_ecu::DockState>& dock_input, Time now,
                      runtime::Problem& why) noexcept {
  if (tool.kind == ToolId::Kind::kUndefined) {
    why.assign("tool id undefined: cannot tell which tool the changer would release");
    return false;
  }
  const dock_ecu::DockState* dock = dock_input.fresh(now);
  if (dock == nullptr) {
    const std::string_view prefix = tool.is_one() ? "cannot confirm " : "";
    const std::string_view subject = tool.is_one() ? tool_name : std::string_view();
    const std::string_view infix = tool.is_one() ? " is home: " : "";
    if (!dock_input.ever_received()) {
      why.format("{}{}{}no Dock ECU State received yet ({})", prefix, subject, infix, dock_input.topic());
    } else {
      why.format("{}{}{}Dock ECU State older than {:.2f} s ({})", prefix, subject, infix,
                 to_seconds(dock_input.timeout()), dock_input.topic());
    }
    return false;
  }
  if (!tool.is_one()) {
    why.clear();
    return true;
  }
  const auto* slot = find_slot(*dock, tool_name);
  if (slot == nullptr) {
    why.format("the Dock ECU State lists no slot '{}': cannot confirm {} is home", tool_name, tool_name);
    return false;
  }
  if (!slot->occupied) {
    why.format("the Dock ECU does not report {} home (slot '{}' empty)", tool_name, tool_name);
    return false;
  }
  why.clear();
  return true;
}

}  // namespace hubrt::rsp_ecu
