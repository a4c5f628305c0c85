// Counts heap allocations made by the calling thread while armed, by interposing malloc and
// friends in the test executable (glibc's __libc_* do the work). Only for plain builds: the
// sanitizers interpose the same functions.
#pragma once

#include <cstddef>

namespace hubrt::dds::test {

// Counts allocations (malloc, calloc, realloc, aligned variants, and so operator new) on this
// thread between construction and destruction; other threads (Cyclone's) are not counted.
class ThreadAllocationCounter {
 public:
  ThreadAllocationCounter() noexcept;
  ~ThreadAllocationCounter();
  ThreadAllocationCounter(const ThreadAllocationCounter&) = delete;
  ThreadAllocationCounter& operator=(const ThreadAllocationCounter&) = delete;
  [[nodiscard]] std::size_t count() const noexcept;
};

}  // namespace hubrt::dds::test
