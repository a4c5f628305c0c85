// What a libmodbus errno means for the caller: which ErrorCode, and whether the connection is gone.
#pragma once

#include <string_view>

#include "hubrt/base/status.h"

namespace hubrt::hal::libmodbus {

struct ModbusFailure {
  ErrorCode code = ErrorCode::kIo;
  bool connection_lost = false;    // close and reconnect (rate-limited)
  bool flush_before_next = false;  // late or partial bytes may still arrive
};

// Maps errno after a failed libmodbus call: ETIMEDOUT → kTimeout; exception responses and
// malformed answers → kProtocol; gateway exceptions → kUnavailable; reset / refused / broken pipe /
// serial I/O error → kUnavailable with connection_lost; EINVAL → kInvalidArgument; anything else
// → kIo with connection_lost (the link's state is unknown).
ModbusFailure classify_modbus_errno(int err) noexcept;

// "illegal data address (exception 02)" for an exception response errno, else an empty view.
std::string_view modbus_exception_name(int err) noexcept;

}  // namespace hubrt::hal::libmodbus
