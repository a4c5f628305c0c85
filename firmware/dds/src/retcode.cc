#include "hubrt/dds/retcode.h"

#include <string>

namespace hubrt::dds {

ErrorCode to_error_code(dds_return_t rc) noexcept {
  if (rc >= 0) return ErrorCode::kOk;
  switch (rc) {
    case DDS_RETCODE_BAD_PARAMETER:
    case DDS_RETCODE_INCONSISTENT_POLICY:
    case DDS_RETCODE_UNSUPPORTED:
      return ErrorCode::kInvalidArgument;
    case DDS_RETCODE_PRECONDITION_NOT_MET:
    case DDS_RETCODE_NOT_ENABLED:
    case DDS_RETCODE_IMMUTABLE_POLICY:
    case DDS_RETCODE_ILLEGAL_OPERATION:
    case DDS_RETCODE_ALREADY_DELETED:
      return ErrorCode::kFailedPrecondition;
    case DDS_RETCODE_TIMEOUT:
      return ErrorCode::kTimeout;
    case DDS_RETCODE_NO_DATA:
    case DDS_RETCODE_NOT_FOUND:
    case DDS_RETCODE_HOST_NOT_FOUND:
      return ErrorCode::kNotFound;
    case DDS_RETCODE_NOT_ALLOWED_BY_SECURITY:
    case DDS_RETCODE_NOT_ALLOWED:
      return ErrorCode::kPermissionDenied;
    case DDS_RETCODE_IN_PROGRESS:
    case DDS_RETCODE_TRY_AGAIN:
      return ErrorCode::kBusy;
    case DDS_RETCODE_OUT_OF_RESOURCES:
    case DDS_RETCODE_NOT_ENOUGH_SPACE:
    case DDS_RETCODE_NO_NETWORK:
    case DDS_RETCODE_NO_CONNECTION:
    case DDS_RETCODE_INTERRUPTED:
      return ErrorCode::kUnavailable;
    case DDS_RETCODE_OUT_OF_RANGE:
      return ErrorCode::kOutOfRange;
    default:
      // DDS_RETCODE_ERROR is Cyclone's "something failed inside": the closest is an I/O failure.
      return ErrorCode::kIo;
  }
}

Status to_status(dds_return_t rc) noexcept {
  return Status(to_error_code(rc));
}

std::string_view retcode_name(dds_return_t rc) noexcept {
  switch (rc) {
    case DDS_RETCODE_OK:
      return "DDS_RETCODE_OK";
    case DDS_RETCODE_ERROR:
      return "DDS_RETCODE_ERROR";
    case DDS_RETCODE_UNSUPPORTED:
      return "DDS_RETCODE_UNSUPPORTED";
    case DDS_RETCODE_BAD_PARAMETER:
      return "DDS_RETCODE_BAD_PARAMETER";
    case DDS_RETCODE_PRECONDITION_NOT_MET:
      return "DDS_RETCODE_PRECONDITION_NOT_MET";
    case DDS_RETCODE_OUT_OF_RESOURCES:
      return "DDS_RETCODE_OUT_OF_RESOURCES";
    case DDS_RETCODE_NOT_ENABLED:
      return "DDS_RETCODE_NOT_ENABLED";
    case DDS_RETCODE_IMMUTABLE_POLICY:
      return "DDS_RETCODE_IMMUTABLE_POLICY";
    case DDS_RETCODE_INCONSISTENT_POLICY:
      return "DDS_RETCODE_INCONSISTENT_POLICY";
    case DDS_RETCODE_ALREADY_DELETED:
      return "DDS_RETCODE_ALREADY_DELETED";
    case DDS_RETCODE_TIMEOUT:
      return "DDS_RETCODE_TIMEOUT";
    case DDS_RETCODE_NO_DATA:
      return "DDS_RETCODE_NO_DATA";
    case DDS_RETCODE_ILLEGAL_OPERATION:
      return "DDS_RETCODE_ILLEGAL_OPERATION";
    case DDS_RETCODE_NOT_ALLOWED_BY_SECURITY:
      return "DDS_RETCODE_NOT_ALLOWED_BY_SECURITY";
    case DDS_RETCODE_IN_PROGRESS:
      return "DDS_RETCODE_IN_PROGRESS";
    case DDS_RETCODE_TRY_AGAIN:
      return "DDS_RETCODE_TRY_AGAIN";
    case DDS_RETCODE_INTERRUPTED:
      return "DDS_RETCODE_INTERRUPTED";
    case DDS_RETCODE_NOT_ALLOWED:
      return "DDS_RETCODE_NOT_ALLOWED";
    case DDS_RETCODE_HOST_NOT_FOUND:
      return "DDS_RETCODE_HOST_NOT_FOUND";
    case DDS_RETCODE_NO_NETWORK:
      return "DDS_RETCODE_NO_NETWORK";
    case DDS_RETCODE_NO_CONNECTION:
      return "DDS_RETCODE_NO_CONNECTION";
    case DDS_RETCODE_NOT_ENOUGH_SPACE:
      return "DDS_RETCODE_NOT_ENOUGH_SPACE";
    case DDS_RETCODE_OUT_OF_RANGE:
      return "DDS_RETCODE_OUT_OF_RANGE";
    case DDS_RETCODE_NOT_FOUND:
      return "DDS_RETCODE_NOT_FOUND";
    default:
      return "DDS_RETCODE_UNKNOWN";
  }
}

Error dds_error(dds_return_t rc, std::string_view what) {
  std::string message(what);
  message += ": ";
  message += retcode_name(rc);
  message += " (";
  message += dds_strretcode(rc);
  message += ')';
  // Cyclone reports a handle that no longer exists (a deleted participant, say) as a bad
  // parameter; say so, because "bad parameter" alone sends people looking at their arguments.
  if (rc == DDS_RETCODE_BAD_PARAMETER) message += "; a deleted or invalid parent entity also gives this";
  return make_error(to_error_code(rc), std::move(message));
}

}  // namespace hubrt::dds
