// The registry of every message type built into this program. Defined by the target
// hubrt_msgs_all, which CMake generates after all hubrt_add_messages() calls (firmware/msgs/cmake/
// HubrtMessages.cmake): link hubrt_msgs_all to use it.
#pragma once

#include "hubrt/msgs/registry.h"

namespace hubrt::msgs {

// Built on first use (thread-safe), then immutable. Never fails: two tables with the same name
// cannot be linked into one program (their idlc descriptors would clash at link time).
const TypeRegistry& all_types() noexcept;

}  // namespace hubrt::msgs
