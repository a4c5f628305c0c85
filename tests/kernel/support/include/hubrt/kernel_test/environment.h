// What the kernel test tier (tests/kernel/run) provides to a test program in its guest, read from
// the HUBRT_* environment variables that guest/run-tests sets. Outside the tier they are unset and
// the functions here return std::nullopt, so a test can skip politely on an ordinary host.
#pragma once

#include <chrono>
#include <optional>
#include <string>

namespace hubrt::kernel_test {

// A gpio-sim chip: the one the tier makes for each test program, or one made by ScopedGpioSimChip.
struct GpioSimChip {
  std::string name;       // "gpiochipN": gpiod_chip_open_by_name()
  std::string dev_path;   // "/dev/gpiochipN": gpiod_chip_open()
  std::string sysfs_dir;  // ".../gpio-sim.K/gpiochipN": holds sim_gpio<offset>/{pull,value}
  std::string label;      // gpiod_chip_open_by_label()
  unsigned num_lines = 0;
};

// True inside the tier's guest (HUBRT_KERNEL_TIER=1). Thread-safe.
[[nodiscard]] bool in_kernel_tier();

// The chip made for this test program (HUBRT_GPIOSIM_CHIP, _DEV, _SYSFS, _LABEL, _LINES).
// std::nullopt outside the tier or when a variable is missing or malformed. Thread-safe.
[[nodiscard]] std::optional<GpioSimChip> gpiosim_chip_from_env();

// The virtual CAN interface (HUBRT_VCAN, "vcan0"), up, made fresh for this test program.
// std::nullopt outside the tier. Thread-safe.
[[nodiscard]] std::optional<std::string> vcan_from_env();

// How long a test waits for hubd to start in the guest (HubProcessOptions::start_patience). The
// guest runs under TCG, and in .ci/run beside the fuzz and arm64 builds (idle priority): there the
// Dock program's six starts took 8.4-13.3 s, against 4.2-6.1 s beside nothing but the TSan build,
// and CI once gave up on one after 20 s. Only a failing start waits this long.
inline constexpr std::chrono::seconds kHubdStartPatience{60};

// Why a kernel-tier test cannot run here, for GTEST_SKIP().
inline constexpr const char* kNotInKernelTier =
    "needs the kernel test tier (vcan, gpio-sim): run it with tests/kernel/run";

}  // namespace hubrt::kernel_test

// In a gtest body or SetUp(): skips the test outside the kernel tier.
#define HUBRT_SKIP_OUTSIDE_KERNEL_TIER()                      \
  do {                                                        \
    if (!::hubrt::kernel_test::in_kernel_tier()) {            \
      GTEST_SKIP() << ::hubrt::kernel_test::kNotInKernelTier; \
    }                                                         \
  } while (false)
