// The Tool ECU's wire types, registered for the typed DDS layer.
#pragma once

#include <string_view>

#include "hubrt/dds/topic_type.h"

#include "tool_ecu.h"
#include "tool_ecu_reflect.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SmartToolCommand_, hub_msgs_msg_dds__SmartToolCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__SmartToolState_, hub_msgs_msg_dds__SmartToolState__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__LiftCommand_, hub_msgs_msg_dds__LiftCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__LiftState_, hub_msgs_msg_dds__LiftState__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__ToolEcuCommand_, hub_msgs_msg_dds__ToolEcuCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__ToolEcuState_, hub_msgs_msg_dds__ToolEcuState__desc);

namespace hubrt::tool_ecu {
using SmartToolCommand = hub_msgs_msg_dds__SmartToolCommand_;
using SmartToolState = hub_msgs_msg_dds__SmartToolState_;
using SmartToolResult = hub_msgs_msg_dds__SmartToolResult_;
using LiftCommand = hub_msgs_msg_dds__LiftCommand_;
using LiftState = hub_msgs_msg_dds__LiftState_;

// The hub layout's types (NodeWiring's HubTypes).
struct ToolEcuTypes {
  using Command = hub_msgs_msg_dds__ToolEcuCommand_;
  using State = hub_msgs_msg_dds__ToolEcuState_;
  static constexpr std::string_view kType = "tool_ecu";
};
}  // namespace hubrt::tool_ecu
