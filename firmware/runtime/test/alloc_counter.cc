#include "alloc_counter.h"

#include <unistd.h>

#include <atomic>
#include <cstddef>
#include <cstdint>
#include <cstring>

#include <sys/prctl.h>
#include <sys/syscall.h>

#include "hubrt/base/sanitizers.h"

#if defined(HUBRT_SANITIZE_ADDRESS) || defined(HUBRT_SANITIZE_THREAD)
#define HUBRT_ALLOC_COUNTER_HOOKS 1
#endif

namespace {
// Initial-exec TLS and a lock-free atomic: counting never allocates, which matters inside malloc.
thread_local std::uint64_t t_count = 0;
std::atomic<std::uint64_t> g_count{0};
// Names of the threads counted apart (null: free slot) and their counts; set once, before use.
std::atomic<const char*> g_thread_names[hubrt::testing::kMaxNamedThreads] = {};
std::atomic<std::uint64_t> g_named_counts[hubrt::testing::kMaxNamedThreads] = {};
std::atomic<bool> g_any_named{false};

// The calling thread's name, straight from the kernel (no allocation, no interceptor).
bool current_thread_name(char (&out)[16]) noexcept {
  return syscall(SYS_prctl, PR_GET_NAME, out, 0, 0, 0) == 0;
}

inline void note() noexcept {
  ++t_count;
  g_count.fetch_add(1, std::memory_order_relaxed);
  if (!g_any_named.load(std::memory_order_relaxed)) return;
  char current[16] = {};
  if (!current_thread_name(current)) return;
  for (std::size_t i = 0; i < hubrt::testing::kMaxNamedThreads; ++i) {
    const char* name = g_thread_names[i].load(std::memory_order_relaxed);
    if (name != nullptr && std::strncmp(current, name, sizeof current) == 0) {
      g_named_counts[i].fetch_add(1, std::memory_order_relaxed);
      return;
    }
  }
}
}  // namespace

#ifdef HUBRT_ALLOC_COUNTER_HOOKS

#if __has_include(<sanitizer/allocator_interface.h>)
#include <sanitizer/allocator_interface.h>
#else
// GCC 12 ships the sanitizer runtimes (libasan, libtsan export this function) but not their
// interface headers; the declaration as in compiler-rt's include/sanitizer/allocator_interface.h.
// NOLINTNEXTLINE(bugprone-reserved-identifier): the sanitizers' name.
extern "C" int __sanitizer_install_malloc_and_free_hooks(void (*malloc_hook)(const volatile void*,
                                                                             std::size_t),
                                                         void (*free_hook)(const volatile void*));
#endif

namespace {
// The sanitizer's allocator calls the malloc hook for every block it hands out (malloc, calloc,
// realloc, the aligned variants, operator new): compiler-rt sanitizer_common RunMallocHooks, called
// from asan_allocator.cpp Allocate() and tsan_mman.cpp invoke_malloc_hook().
void on_malloc(const volatile void* /*ptr*/, std::size_t /*size*/) {
  note();
}
void on_free(const volatile void* /*ptr*/) {}

// Installed before main(), so that nothing the test measures runs before it.
[[maybe_unused]] const int g_installed = __sanitizer_install_malloc_and_free_hooks(on_malloc, on_free);
}  // namespace

namespace hubrt::testing {
const char* allocation_counting_method() noexcept {
  return "sanitizer hooks";
}
}  // namespace hubrt::testing

#else

// glibc's own implementations, reachable under these names when the executable defines malloc.
// NOLINTBEGIN(bugprone-reserved-identifier,cppcoreguidelines-no-malloc): glibc's names.
extern "C" {
void* __libc_malloc(std::size_t size) noexcept;
void* __libc_calloc(std::size_t n, std::size_t size) noexcept;
void* __libc_realloc(void* ptr, std::size_t size) noexcept;
void* __libc_memalign(std::size_t alignment, std::size_t size) noexcept;
void __libc_free(void* ptr) noexcept;
}

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
const char* allocation_counting_method() noexcept {
  return "interposed malloc";
}
}  // namespace hubrt::testing

#endif

namespace hubrt::testing {

std::uint64_t thread_allocations() noexcept {
  return t_count;
}
std::uint64_t process_allocations() noexcept {
  return g_count.load(std::memory_order_relaxed);
}
void count_allocations_of_threads_named(std::initializer_list<const char*> names) noexcept {
  std::size_t i = 0;
  for (const char* name : names) {
    if (i == kMaxNamedThreads) break;
    g_thread_names[i++].store(name, std::memory_order_relaxed);
  }
  g_any_named.store(i > 0, std::memory_order_relaxed);
}
std::uint64_t named_thread_allocations(const char* name) noexcept {
  for (std::size_t i = 0; i < kMaxNamedThreads; ++i) {
    const char* named = g_thread_names[i].load(std::memory_order_relaxed);
    if (named != nullptr && std::strcmp(named, name) == 0)
      return g_named_counts[i].load(std::memory_order_relaxed);
  }
  return 0;
}

}  // namespace hubrt::testing
