// The operator hub's message types: the classes generated from operator_panel.idl and
// operator_hub.idl (firmware/msgs/README.md, "Typed accessors"); their _typed.h headers also
// register the topics.
#pragma once

#include <string_view>

#include "operator_hub_reflect.h"
#include "operator_hub_typed.h"
#include "operator_panel_reflect.h"
#include "operator_panel_typed.h"

namespace hubrt::operator_hub {

// The C structs on the wire, for tests that talk DDS directly (logic uses the classes).
using OperatorPanelCommand = hub_msgs::OperatorPanelCommand::Wire;
using OperatorPanelState = hub_msgs::OperatorPanelState::Wire;

// The hub layout's types (NodeWiring's HubTypes).
struct OperatorHubTypes {
  using Command = hub_msgs::OperatorHubCommandView;
  using State = hub_msgs::OperatorHubState;
  static constexpr std::string_view kType = "operator_hub";
};

}  // namespace hubrt::operator_hub
