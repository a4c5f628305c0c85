// The crash-safe output table: one 32-bit atomic word per slot, so that entering, leaving and
// reading an entry are single lock-free operations a signal handler may race with.
#include "crash_safe_table.h"

#include <array>
#include <atomic>
#include <cerrno>
#include <cstdint>

#include <linux/gpio.h>
#include <sys/ioctl.h>

#include "hubrt/hal/linux/crash_safe_outputs.h"

namespace hubrt::hal {
namespace {

// Entry layout: bit 31 in use, bit 30 safe level, bit 29 active-low, bits 24..28 a check of the
// descriptor (a stray write rarely gets it right), bits 0..23 the descriptor. A descriptor beyond
// 24 bits (more than 16 million open files) is not entered.
constexpr std::uint32_t kInUse = 1U << 31;
constexpr std::uint32_t kSafe = 1U << 30;
constexpr std::uint32_t kActiveLow = 1U << 29;
constexpr unsigned kCheckShift = 24;
constexpr std::uint32_t kCheckMask = 0x1FU;
constexpr std::uint32_t kFdMask = 0xFFFFFFU;

using Slot = std::atomic<std::uint32_t>;
static_assert(Slot::is_always_lock_free, "a signal handler may only touch lock-free atomics");

std::array<Slot, kCrashSafeCapacity> g_slots{};  // zero: free

constexpr std::uint32_t check_of(std::uint32_t fd) noexcept {
  return (fd ^ (fd >> 5U) ^ (fd >> 10U) ^ (fd >> 15U) ^ (fd >> 20U) ^ 0x15U) & kCheckMask;
}

bool valid(std::uint32_t entry) noexcept {
  if ((entry & kInUse) == 0) return false;
  const std::uint32_t fd = entry & kFdMask;
  return ((entry >> kCheckShift) & kCheckMask) == check_of(fd);
}

// The line's bias toward its safe level: the electrical level is the logical one inverted for an
// active-low line.
std::uint32_t bias_toward_safe(bool safe, bool active_low) noexcept {
  return safe != active_low ? GPIOHANDLE_REQUEST_BIAS_PULL_UP : GPIOHANDLE_REQUEST_BIAS_PULL_DOWN;
}

}  // namespace

namespace gpiod_detail {

int enter_crash_safe_output(int fd, bool safe, bool active_low) noexcept {
  if (fd < 0 || static_cast<std::uint32_t>(fd) > kFdMask) return -1;
  const auto bits = static_cast<std::uint32_t>(fd);
  const std::uint32_t entry =
      kInUse | (safe ? kSafe : 0U) | (active_low ? kActiveLow : 0U) | (check_of(bits) << kCheckShift) | bits;
  for (std::size_t i = 0; i < g_slots.size(); ++i) {
    std::uint32_t expected = 0;
    if (g_slots[i].compare_exchange_strong(expected, entry, std::memory_order_release,
                                           std::memory_order_relaxed)) {
      return static_cast<int>(i);
    }
  }
  return -1;
}

void leave_crash_safe_output(int slot) noexcept {
  if (slot < 0 || static_cast<std::size_t>(slot) >= g_slots.size()) return;
  g_slots[static_cast<std::size_t>(slot)].store(0, std::memory_order_release);
}

}  // namespace gpiod_detail

CrashSafeResult drive_outputs_safe_from_crash() noexcept {
  const int saved_errno = errno;
  CrashSafeResult result;
  for (const Slot& slot : g_slots) {
    const std::uint32_t entry = slot.load(std::memory_order_acquire);
    if (!valid(entry)) continue;
    const int fd = static_cast<int>(entry & kFdMask);
    const bool safe = (entry & kSafe) != 0;
    const bool active_low = (entry & kActiveLow) != 0;
    // Logical levels: the request carries the active-low flag, the kernel inverts
    // (linux/gpio.h, struct gpiohandle_data).
    gpiohandle_data data{};
    data.values[0] = safe ? 1 : 0;
    if (::ioctl(fd, GPIOHANDLE_SET_LINE_VALUES_IOCTL, &data) < 0) {
      ++result.failed;
      continue;
    }
    ++result.driven;
    // Same direction and level, plus the bias (gpiolib applies a requested bias to output lines
    // too: gpiod_direction_output() calls gpio_set_bias()). Refused by kernels before 5.5; the
    // level written above is what matters while the process still holds the line.
    gpiohandle_config config{};
    config.flags = GPIOHANDLE_REQUEST_OUTPUT | (active_low ? GPIOHANDLE_REQUEST_ACTIVE_LOW : 0U) |
                   bias_toward_safe(safe, active_low);
    config.default_values[0] = safe ? 1 : 0;
    (void)::ioctl(fd, GPIOHANDLE_SET_CONFIG_IOCTL, &config);
  }
  errno = saved_errno;
  return result;
}

std::size_t crash_safe_output_count() noexcept {
  std::size_t count = 0;
  for (const Slot& slot : g_slots) {
    if (valid(slot.load(std::memory_order_acquire))) ++count;
  }
  return count;
}

}  // namespace hubrt::hal
