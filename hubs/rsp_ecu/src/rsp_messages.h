// The RSP ECU's wire types, registered for the typed DDS layer.
#pragma once

#include <string_view>

#include "hubrt/dds/topic_type.h"

#include "rsp.h"
#include "rsp_reflect.h"

HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspCommand_, hub_msgs_msg_dds__RspCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspState_, hub_msgs_msg_dds__RspState__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspEcuCommand_, hub_msgs_msg_dds__RspEcuCommand__desc);
HUBRT_DDS_TOPIC_TYPE(hub_msgs_msg_dds__RspEcuState_, hub_msgs_msg_dds__RspEcuState__desc);

namespace hubrt::rsp_ecu {
using RspCommand = hub_msgs_msg_dds__RspCommand_;
using RspState = hub_msgs_msg_dds__RspState_;

// The hub layout's types (NodeWiring's HubTypes).
struct RspEcuTypes {
  using Command = hub_msgs_msg_dds__RspEcuCommand_;
  using State = hub_msgs_msg_dds__RspEcuState_;
  static constexpr std::string_view kType = "rsp_ecu";
};
}  // namespace hubrt::rsp_ecu
