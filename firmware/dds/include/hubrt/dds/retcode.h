// Turning Cyclone DDS return codes into hubrt errors: a Status on the hot path (code only, no
// allocation), an Error with a message naming the operation, topic or domain everywhere else.
#pragma once

#include <string_view>

#include <dds/dds.h>

#include "hubrt/base/status.h"

namespace hubrt::dds {

// The ErrorCode a Cyclone return code stands for; kOk for DDS_RETCODE_OK and for positive values
// (Cyclone returns entity handles and counts through the same type). Thread-safe.
ErrorCode to_error_code(dds_return_t rc) noexcept;

// Status for a Cyclone return code: ok for rc >= 0. Never allocates. Thread-safe.
Status to_status(dds_return_t rc) noexcept;

// The symbolic name of a Cyclone return code, e.g. "DDS_RETCODE_BAD_PARAMETER";
// "DDS_RETCODE_<n>" is not produced: unknown codes give "DDS_RETCODE_UNKNOWN". Thread-safe.
std::string_view retcode_name(dds_return_t rc) noexcept;

// An Error whose message reads "<what>: DDS_RETCODE_X (<Cyclone's explanation>)", e.g.
// "create reader on 'rt/dock/command' in domain 7: DDS_RETCODE_BAD_PARAMETER (Bad Parameter)".
// `what` says what was being done and on which topic/domain. Precondition: rc < 0. Thread-safe.
Error dds_error(dds_return_t rc, std::string_view what);

}  // namespace hubrt::dds
