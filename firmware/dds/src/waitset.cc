#include "hubrt/dds/waitset.h"

#include <algorithm>
#include <string>

#include "hubrt/dds/retcode.h"

namespace hubrt::dds {

Expected<WaitSet> WaitSet::create(const Participant& participant) {
  const std::string where = " in domain " + std::to_string(participant.domain_id());
  EntityHandle guard(dds_create_guardcondition(participant.handle()));
  if (guard.get() < 0) return dds_error(guard.get(), "create guard condition for waitset" + where);
  EntityHandle waitset(dds_create_waitset(participant.handle()));
  if (waitset.get() < 0) return dds_error(waitset.get(), "create waitset" + where);
  const dds_return_t rc = dds_waitset_attach(waitset.get(), guard.get(), kWakeToken);
  if (rc < 0) return dds_error(rc, "attach guard condition to waitset" + where);
  return WaitSet(std::move(guard), std::move(waitset));
}

Expected<void> WaitSet::attach(const ReadCondition& condition, Token token) {
  if (token == kWakeToken) {
    return make_error(ErrorCode::kInvalidArgument,
                      "attach to waitset: token kWakeToken is reserved for wake()");
  }
  const dds_return_t rc = dds_waitset_attach(waitset_.get(), condition.handle(), token);
  if (rc < 0) return dds_error(rc, "attach read condition to waitset (token " + std::to_string(token) + ")");
  return {};
}

Expected<void> WaitSet::detach(const ReadCondition& condition) {
  const dds_return_t rc = dds_waitset_detach(waitset_.get(), condition.handle());
  if (rc < 0) return dds_error(rc, "detach read condition from waitset");
  return {};
}

Result<std::size_t> WaitSet::wait(std::span<Token> fired, Duration timeout) noexcept {
  const dds_return_t n = dds_waitset_wait(waitset_.get(), fired.data(), fired.size(), timeout.count());
  if (n < 0) return to_status(n);
  // Cyclone returns how many fired, which may exceed what fit into `fired`.
  const std::size_t written = std::min(static_cast<std::size_t>(n), fired.size());
  for (std::size_t i = 0; i < written; ++i) {
    if (fired[i] == kWakeToken) {
      // Reset by taking, so a wake() racing with this wait is never lost: it either is the one
      // consumed here or sets the guard again for the next wait.
      bool triggered = false;
      const dds_return_t rc = dds_take_guardcondition(guard_.get(), &triggered);
      if (rc < 0) return to_status(rc);
    }
  }
  return written;
}

Status WaitSet::wake() noexcept {
  return to_status(dds_set_guardcondition(guard_.get(), true));
}

}  // namespace hubrt::dds
