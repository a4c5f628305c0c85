#include "alloc_counter.h"

#include <atomic>
#include <cstddef>
#include <cstdint>

// glibc's own implementations, reachable under these names when the executable defines malloc.
// NOLINTBEGIN(bugprone-reserved-identifier,cppcoreguidelines-no-malloc): glibc's names.
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t n, std::size_t size) noexcept;
void* __libc_realloc(void* ptr, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* ptr) noexcept;
}

namespace {
// Initial-exec TLS and a lock-free atomic: counting never allocates, which matters inside malloc.
thread_local std::uint64_t t_count = 0;
std::atomic<std::uint64_t> g_count{0};

inline void note() noexcept {
  ++t_count;
  g_count.fetch_add(1, std::memory_order_relaxed);
}
}  // namespace

extern "C" {
void* malloc(std::size_t size) noexcept {
  note();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) noexcept {
  note();
  return __libc_calloc(n, size);
}
void* realloc(void* ptr, std::size_t size) noexcept {
  note();
  return __libc_realloc(ptr, size);
}
void* memalign(std::size_t alignment, std::size_t size) noexcept {
  note();
  return __libc_memalign(alignment, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) noexcept {
  note();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) noexcept {
  note();
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr) return 12;  // ENOMEM
  *out = p;
  return 0;
}
void free(void* ptr) noexcept {
  __libc_free(ptr);
}
}
// NOLINTEND(bugprone-reserved-identifier,cppcoreguidelines-no-malloc)

namespace hubrt::testing {

std::uint64_t thread_allocations() noexcept {
  return t_count;
}
std::uint64_t process_allocations() noexcept {
  return g_count.load(std::memory_order_relaxed);
}

}  // namespace hubrt::testing
