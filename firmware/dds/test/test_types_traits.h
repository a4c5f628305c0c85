// Registers the test IDL types with the typed API.
#pragma once

#include "hubrt/dds/topic_type.h"

#include "test_types.h"

HUBRT_DDS_TOPIC_TYPE(hubrt_test_msg_dds__Ping_, hubrt_test_msg_dds__Ping__desc);
HUBRT_DDS_TOPIC_TYPE(hubrt_test_msg_dds__Counter_, hubrt_test_msg_dds__Counter__desc);

namespace hubrt::dds::test {
using Ping = hubrt_test_msg_dds__Ping_;
using Counter = hubrt_test_msg_dds__Counter_;
}  // namespace hubrt::dds::test
