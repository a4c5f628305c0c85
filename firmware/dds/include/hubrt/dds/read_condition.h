// A condition that is triggered while a reader holds samples, for waiting on a WaitSet.
#pragma once

#include <dds/dds.h>

#include "hubrt/base/status.h"
#include "hubrt/dds/entity.h"
#include "hubrt/dds/reader.h"

namespace hubrt::dds {

// Triggered while the reader has samples matching `mask` (default: any sample at all, so it
// stays triggered until everything was taken). Move-only; dds_delete() on destruction; deleted
// with its reader too. Thread-safety: as Reader.
class ReadCondition {
 public:
  // Errors: Cyclone's refusal as "create read condition on 'rt/...': DDS_RETCODE_...".
  static Expected<ReadCondition> create(const UntypedReader& reader, std::uint32_t mask = DDS_ANY_STATE);
  template <TopicType T>
  static Expected<ReadCondition> create(const Reader<T>& reader, std::uint32_t mask = DDS_ANY_STATE) {
    return create(reader.untyped(), mask);
  }

  [[nodiscard]] dds_entity_t handle() const noexcept { return handle_.get(); }

 private:
  explicit ReadCondition(EntityHandle handle) noexcept : handle_(std::move(handle)) {}
  EntityHandle handle_;
};

}  // namespace hubrt::dds
