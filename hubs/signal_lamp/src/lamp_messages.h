// The signal lamp's message types: the classes generated from lamp.idl and signal_lamp.idl
// (firmware/msgs/README.md, "Typed accessors"); their _typed.h headers also register the topics.
#pragma once

#include <string_view>

#include "lamp_reflect.h"
#include "lamp_typed.h"
#include "signal_lamp_reflect.h"
#include "signal_lamp_typed.h"

namespace hubrt::signal_lamp {

// The C structs on the wire, for tests that talk DDS directly (logic uses the classes).
using LampCommand = hub_msgs::LampCommand::Wire;
using LampState = hub_msgs::LampState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct SignalLampTypes {
  using Command = hub_msgs::SignalLampCommandView;
  using State = hub_msgs::SignalLampState;
  static constexpr std::string_view kType = "signal_lamp";
};

}  // namespace hubrt::signal_lamp
