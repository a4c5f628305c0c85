// The Tool ECU's message types: the classes generated from tool_ecu.idl (firmware/msgs/README.md,
// "Typed accessors"); tool_ecu_typed.h also registers the topics.
#pragma once

#include <string_view>

#include "tool_ecu_reflect.h"
#include "tool_ecu_typed.h"

namespace hubrt::tool_ecu {

// The C structs on the wire, for tools and tests that talk DDS directly (logic uses the classes).
using SmartToolCommand = hub_msgs::SmartToolCommand::Wire;
using SmartToolState = hub_msgs::SmartToolState::Wire;
using SmartToolResult = hub_msgs::SmartToolResult::Wire;
using LiftCommand = hub_msgs::LiftCommand::Wire;
using LiftState = hub_msgs::LiftState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct ToolEcuTypes {
  using Command = hub_msgs::ToolEcuCommandView;
  using State = hub_msgs::ToolEcuState;
  static constexpr std::string_view kType = "tool_ecu";
};

}  // namespace hubrt::tool_ecu
