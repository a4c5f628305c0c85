// Ownership of one Cyclone entity handle: deleted exactly once, when the owner goes away.
#pragma once

#include <utility>

#include <dds/dds.h>

namespace hubrt::dds {

// Move-only owner of a dds_entity_t; calls dds_delete() in the destructor. Deleting an entity
// deletes its children too (participant -> topics, readers, writers, conditions), so a child
// whose parent was destroyed first is already gone: its own dds_delete() then just fails
// harmlessly (Cyclone handles are checked, never reused for another entity in practice).
// Thread-safety: not thread-safe; the handle it exposes may be used from any thread, as Cyclone
// allows.
class EntityHandle {
 public:
  EntityHandle() noexcept = default;
  // Takes ownership of `handle` (must be > 0 or 0 for "none").
  explicit EntityHandle(dds_entity_t handle) noexcept : handle_(handle) {}
  ~EntityHandle() { reset(); }

  EntityHandle(const EntityHandle&) = delete;
  EntityHandle& operator=(const EntityHandle&) = delete;
  EntityHandle(EntityHandle&& other) noexcept : handle_(std::exchange(other.handle_, 0)) {}
  EntityHandle& operator=(EntityHandle&& other) noexcept {
    if (this != &other) {
      reset();
      handle_ = std::exchange(other.handle_, 0);
    }
    return *this;
  }

  [[nodiscard]] dds_entity_t get() const noexcept { return handle_; }
  [[nodiscard]] bool valid() const noexcept { return handle_ > 0; }
  // Deletes the entity now (and its children); the handle becomes 0.
  void reset() noexcept {
    if (handle_ > 0) (void)dds_delete(handle_);
    handle_ = 0;
  }

 private:
  dds_entity_t handle_ = 0;
};

}  // namespace hubrt::dds
