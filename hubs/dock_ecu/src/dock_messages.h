// The Dock ECU's wire types, registered for the typed DDS layer.
#pragma once

#include <string_view>

#include "hubrt/dds/topic_type.h"

#include "dock.h"
#include "dock_ecu.h"
#include "dock_ecu_reflect.h"
#include "dock_reflect.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockCommand_, hub_msgs_msg_dds__DockCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockState_, hub_msgs_msg_dds__DockState__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockEcuCommand_, hub_msgs_msg_dds__DockEcuCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockEcuState_, hub_msgs_msg_dds__DockEcuState__desc);

namespace hubrt::dock_ecu {
using DockCommand = hub_msgs_msg_dds__DockCommand_;
using DockState = hub_msgs_msg_dds__DockState_;

// The hub layout's types (NodeWiring's HubTypes).
struct DockEcuTypes {
  using Command = hub_msgs_msg_dds__DockEcuCommand_;
  using State = hub_msgs_msg_dds__DockEcuState_;
  static constexpr std::string_view kType = "dock_ecu";
};
}  // namespace hubrt::dock_ecu
