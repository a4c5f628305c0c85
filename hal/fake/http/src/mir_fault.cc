#include "hubrt/hal/fake/mir_sim_server.h"

namespace hubrt::hal::fake {

Result<MirServerFault> parse_mir_fault(std::string_view name) noexcept {
  if (name == "answer") return MirServerFault::kNone;
  if (name == "server_error") return MirServerFault::kServerError;
  if (name == "unauthorized") return MirServerFault::kUnauthorized;
  if (name == "slow") return MirServerFault::kSlow;
  if (name == "stop_answering") return MirServerFault::kNoAnswer;
  if (name == "malformed_json") return MirServerFault::kMalformedJson;
  return Status(ErrorCode::kNotFound);
}

}  // namespace hubrt::hal::fake
