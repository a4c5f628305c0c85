#include "unlock_interlock.h"

#include <optional>

namespace hubrt::rsp_ecu {
namespace {

// The slot of `tool` in the Dock ECU State, or nothing when the dock does not list it.
std::optional<hub_msgs::DockSlotView> find_slot(const hub_msgs::DockStateView& dock,
                                                std::string_view tool) noexcept {
  for (const hub_msgs::DockSlotView slot : dock.slots()) {
    if (slot.name() == tool) return slot;
  }
  return std::nullopt;
}

}  // namespace

bool unlock_permitted(const ToolId& tool, std::string_view tool_name,
                      const hub_api::RemoteState<hub_msgs::DockStateView>& dock_input, Time now,
                      runtime::Problem& why) noexcept {
  if (tool.kind == ToolId::Kind::kUndefined) {
    why.assign("tool id undefined: cannot tell which tool the changer would release");
    return false;
  }
  const std::optional<hub_msgs::DockStateView> dock = dock_input.fresh(now);
  if (!dock) {
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
  const std::optional<hub_msgs::DockSlotView> slot = find_slot(*dock, tool_name);
  if (!slot) {
    why.format("the Dock ECU State lists no slot '{}': cannot confirm {} is home", tool_name, tool_name);
    return false;
  }
  if (!slot->occupied()) {
    why.format("the Dock ECU does not report {} home (slot '{}' empty)", tool_name, tool_name);
    return false;
  }
  why.clear();
  return true;
}

}  // namespace hubrt::rsp_ecu
