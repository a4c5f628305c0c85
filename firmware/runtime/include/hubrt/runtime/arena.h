// A bump allocator over storage reserved once. Used to hold the deep copy of the echoed command
// so that copying a new command in the cycle never touches the heap.
#pragma once

#include <cstddef>
#include <memory>

namespace hubrt::runtime {

class Arena {
 public:
  explicit Arena(std::size_t capacity)
      : storage_(std::make_unique<std::byte[]>(capacity)), capacity_(capacity) {}

  // Returns `size` bytes aligned to `align`, or nullptr when the arena is exhausted.
  void* allocate(std::size_t size, std::size_t align = alignof(std::max_align_t)) noexcept {
    const std::size_t start = (used_ + align - 1) / align * align;
    if (start > capacity_ || size > capacity_ - start) return nullptr;
    used_ = start + size;
    return storage_.get() + start;
  }
  // Forgets everything allocated; the memory is reused by the next allocations.
  void reset() noexcept { used_ = 0; }
  [[nodiscard]] std::size_t used() const noexcept { return used_; }
  [[nodiscard]] std::size_t capacity() const noexcept { return capacity_; }

 private:
  std::unique_ptr<std::byte[]> storage_;
  std::size_t capacity_;
  std::size_t used_ = 0;
};

}  // namespace hubrt::runtime
