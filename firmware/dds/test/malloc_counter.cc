#include "malloc_counter.h"

#include <cstddef>

// glibc's real implementations, which stay reachable under these names when the executable
// defines its own malloc.
// NOLINTBEGIN(bugprone-reserved-identifier): glibc's names.
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t n, std::size_t size) noexcept;
void* __libc_realloc(void* ptr, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* ptr) noexcept;
}
// NOLINTEND(bugprone-reserved-identifier)

namespace {
// Initial-exec TLS in the executable: reading it never allocates, which matters inside malloc.
thread_local bool g_armed = false;
thread_local std::size_t g_count = 0;

inline void note() noexcept {
  if (g_armed) ++g_count;
}
}  // namespace

extern "C" {
// NOLINTBEGIN(cppcoreguidelines-no-malloc,bugprone-reserved-identifier)
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
// NOLINTEND(cppcoreguidelines-no-malloc,bugprone-reserved-identifier)
}

namespace hubrt::dds::test {

ThreadAllocationCounter::ThreadAllocationCounter() noexcept {
  g_count = 0;
  g_armed = true;
}
ThreadAllocationCounter::~ThreadAllocationCounter() {
  g_armed = false;
}
std::size_t ThreadAllocationCounter::count() const noexcept {
  return g_count;
}

}  // namespace hubrt::dds::test
