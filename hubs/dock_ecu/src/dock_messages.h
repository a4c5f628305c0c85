// The Dock ECU's wire types, registered for the typed DDS layer.
#pragma once

#include "hubrt/dds/topic_type.h"

#include "dock.h"
#include "dock_reflect.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockCommand_, hub_msgs_msg_dds__DockCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__DockState_, hub_msgs_msg_dds__DockState__desc);

namespace hubrt::dock_ecu {
using DockCommand = hub_msgs_msg_dds__DockCommand_;
using DockState = hub_msgs_msg_dds__DockState_;
}  // namespace hubrt::dock_ecu
