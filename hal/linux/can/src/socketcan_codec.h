// Conversions between the HAL's CAN types and the kernel's (struct can_frame, struct can_filter),
// and the error-frame → bus-state rules. Pure functions, tested without a CAN-capable kernel.
#pragma once

#include <span>
#include <vector>

#include <linux/can.h>

#include "hubrt/base/status.h"
#include "hubrt/hal/can_bus.h"

namespace hubrt::hal::socketcan {

// kInvalidArgument when the frame cannot be sent (len > 8, id wider than its format).
Status to_kernel_frame(const CanFrame& frame, can_frame& out) noexcept;
// Precondition: `in` is a data or remote frame (no CAN_ERR_FLAG).
CanFrame from_kernel_frame(const can_frame& in) noexcept;

// The HAL's filter rule ("extended flag must match", "no filters = everything") in CAN_RAW_FILTER
// terms. kInvalidArgument for an id or mask wider than its format, or more than 512 filters.
// `out` is replaced; an empty input gives one match-all filter (the kernel would read zero
// filters as "receive nothing").
Status to_kernel_filters(std::span<const CanFilter> filters, std::vector<can_filter>& out);

// Updates `status` from one error frame (CAN_ERR_FLAG set): counts it, takes the error counters
// when present (CAN_ERR_CNT), and moves the state on controller-state, bus-off and restart reports.
void apply_error_frame(const can_frame& frame, CanBusStatus& status) noexcept;

// libsocketcan's CAN_STATE_* (linux/can/netlink.h) as a bus state.
CanBusState from_netlink_state(int state) noexcept;

}  // namespace hubrt::hal::socketcan
