// Blocking until one of several conditions fires, with a built-in way to wake the waiter.
#pragma once

#include <cstddef>
#include <cstdint>
#include <span>

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/base/time.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/participant.h"
#include "hubrt/dds/read_condition.h"

namespace hubrt::dds {

// A Cyclone waitset plus a guard condition that wake() triggers. Conditions are attached with a
// caller-chosen token that wait() reports back when they fire. Move-only; dds_delete() on
// destruction (the participant's deletion also deletes it).
// Thread-safety: wake() may be called from any thread, including data-available callbacks;
// attach/detach/wait from one thread at a time.
class WaitSet {
 public:
  using Token = dds_attach_t;
  // Reported by wait() when wake() was called; do not attach anything with this token.
  static constexpr Token kWakeToken = -1;

  // Errors: Cyclone's refusal as "create waitset in domain N: DDS_RETCODE_...".
  static Expected<WaitSet> create(const Participant& participant);

  // The condition's reader must belong to the participant the waitset was created from.
  // Errors: Cyclone's refusal (e.g. condition of another participant, already attached);
  // kInvalidArgument for token == kWakeToken.
  Expected<void> attach(const ReadCondition& condition, Token token);
  Expected<void> detach(const ReadCondition& condition);

  // Blocks until something attached is triggered, wake() was called, or `timeout` passes.
  // Writes the tokens of what fired into `fired` (at most fired.size(); kWakeToken for wake())
  // and returns how many it wrote: 0 means the timeout passed. A wake is consumed by the wait
  // that reports it; read conditions stay triggered until their samples are taken.
  // Allocates nothing on our side. Errors: Cyclone's code (e.g. deleted waitset).
  Result<std::size_t> wait(std::span<Token> fired, Duration timeout) noexcept;

  // Makes the current or next wait() return with kWakeToken. Wakes are not counted: several
  // before one wait() give one kWakeToken. Errors: Cyclone's code (deleted waitset).
  Status wake() noexcept;

  [[nodiscard]] dds_entity_t handle() const noexcept { return waitset_.get(); }

 private:
  WaitSet(EntityHandle guard, EntityHandle waitset) noexcept
      : guard_(std::move(guard)), waitset_(std::move(waitset)) {}

  EntityHandle guard_;
  EntityHandle waitset_;
};

}  // namespace hubrt::dds
