// The RSP ECU's message types: the classes generated from rsp.idl (firmware/msgs/README.md,
// "Typed accessors"); rsp_typed.h also registers the topics.
#pragma once

#include <string_view>

#include "rsp_reflect.h"
#include "rsp_typed.h"

namespace hubrt::rsp_ecu {

// The C structs on the wire, for tools and tests that talk DDS directly (logic uses the classes).
using RspCommand = hub_msgs::RspCommand::Wire;
using RspState = hub_msgs::RspState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct RspEcuTypes {
  using Command = hub_msgs::RspEcuCommandView;
  using State = hub_msgs::RspEcuState;
  static constexpr std::string_view kType = "rsp_ecu";
};

}  // namespace hubrt::rsp_ecu
