// The Dock ECU's message types: the classes generated from dock.idl and dock_ecu.idl
// (firmware/msgs/README.md, "Typed accessors"); their _typed.h headers also register the topics.
#pragma once

#include <string_view>

#include "dock_ecu_reflect.h"
#include "dock_ecu_typed.h"
#include "dock_reflect.h"
#include "dock_typed.h"

namespace hubrt::dock_ecu {

// The C structs on the wire, for tools and tests that talk DDS directly (logic uses the classes).
using DockCommand = hub_msgs::DockCommand::Wire;
using DockState = hub_msgs::DockState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct DockEcuTypes {
  using Command = hub_msgs::DockEcuCommandView;
  using State = hub_msgs::DockEcuState;
  static constexpr std::string_view kType = "dock_ecu";
};

}  // namespace hubrt::dock_ecu
