#include "modbus_errors.h"

#include <cerrno>

#include <modbus/modbus.h>

namespace hubrt::hal::libmodbus {

ModbusFailure classify_modbus_errno(int err) noexcept {
  switch (err) {
    case ETIMEDOUT:
      return {ErrorCode::kTimeout, false, true};
    case EMBXILFUN:
    case EMBXILADD:
    case EMBXILVAL:
    case EMBXSFAIL:
    case EMBXACK:
    case EMBXSBUSY:
    case EMBXNACK:
    case EMBXMEMPAR:
      return {ErrorCode::kProtocol, false, false};
    // A gateway answering for a unit it cannot reach: the unit is unavailable, the link is fine.
    case EMBXGPATH:
    case EMBXGTAR:
      return {ErrorCode::kUnavailable, false, false};
    case EMBBADCRC:
    case EMBBADDATA:
    case EMBBADEXC:
    case EMBUNKEXC:
    case EMBMDATA:
    case EMBBADSLAVE:
      return {ErrorCode::kProtocol, false, true};
    case ECONNRESET:
    case ECONNREFUSED:
    case ECONNABORTED:
    case EPIPE:
    case ENOTCONN:
    case EBADF:
    case ENETDOWN:
    case ENETUNREACH:
    case EHOSTUNREACH:
    case EIO:
    case ENXIO:
    case ENODEV:
      return {ErrorCode::kUnavailable, true, false};
    case EINVAL:
      return {ErrorCode::kInvalidArgument, false, false};
    default:
      return {ErrorCode::kIo, true, false};
  }
}

std::string_view modbus_exception_name(int err) noexcept {
  switch (err) {
    case EMBXILFUN:
      return "illegal function (exception 01)";
    case EMBXILADD:
      return "illegal data address (exception 02)";
    case EMBXILVAL:
      return "illegal data value (exception 03)";
    case EMBXSFAIL:
      return "server device failure (exception 04)";
    case EMBXACK:
      return "acknowledge (exception 05)";
    case EMBXSBUSY:
      return "server device busy (exception 06)";
    case EMBXNACK:
      return "negative acknowledge (exception 07)";
    case EMBXMEMPAR:
      return "memory parity error (exception 08)";
    case EMBXGPATH:
      return "gateway path unavailable (exception 0A)";
    case EMBXGTAR:
      return "gateway target failed to respond (exception 0B)";
    default:
      return {};
  }
}

}  // namespace hubrt::hal::libmodbus
