// The HUBRT_* contract between guest/run-tests and kernel-tier tests, checked on the host.
#include "hubrt/kernel_test/environment.h"

#include <cstdlib>

#include <gtest/gtest.h>

namespace hubrt::kernel_test {
namespace {

// Sets the variables for one test and restores "unset" after it (the host never has them).
class KernelTierEnvironmentTest : public ::testing::Test {
 protected:
  void TearDown() override {
    for (const char* name : kNames) ::unsetenv(name);  // NOLINT(concurrency-mt-unsafe): single-threaded test
  }
  static void set(const char* name, const char* value) {
    ::setenv(name, value, 1);  // NOLINT(concurrency-mt-unsafe): single-threaded test
  }
  static void set_complete_chip() {
    set("HUBRT_KERNEL_TIER", "1");
    set("HUBRT_GPIOSIM_CHIP", "gpiochip1");
    set("HUBRT_GPIOSIM_DEV", "/dev/gpiochip1");
    set("HUBRT_GPIOSIM_SYSFS", "/sys/devices/platform/gpio-sim.0/gpiochip1");
    set("HUBRT_GPIOSIM_LABEL", "hubrt-kt1");
    set("HUBRT_GPIOSIM_LINES", "16");
  }
  static constexpr const char* kNames[] = {"HUBRT_KERNEL_TIER",  "HUBRT_VCAN",          "HUBRT_GPIOSIM_CHIP",
                                           "HUBRT_GPIOSIM_DEV",  "HUBRT_GPIOSIM_SYSFS", "HUBRT_GPIOSIM_LABEL",
                                           "HUBRT_GPIOSIM_LINES"};
};

TEST_F(KernelTierEnvironmentTest, CompleteVariablesDescribeTheChipAndTheInterface) {
  set_complete_chip();
  set("HUBRT_VCAN", "vcan0");
  ASSERT_TRUE(in_kernel_tier());
  auto chip = gpiosim_chip_from_env();
  ASSERT_TRUE(chip);
  EXPECT_EQ(chip->name, "gpiochip1");
  EXPECT_EQ(chip->dev_path, "/dev/gpiochip1");
  EXPECT_EQ(chip->sysfs_dir, "/sys/devices/platform/gpio-sim.0/gpiochip1");
  EXPECT_EQ(chip->label, "hubrt-kt1");
  EXPECT_EQ(chip->num_lines, 16U);
  EXPECT_EQ(vcan_from_env(), "vcan0");
}

TEST_F(KernelTierEnvironmentTest, WithoutTheTierMarkerNothingIsReported) {
  set_complete_chip();
  set("HUBRT_VCAN", "vcan0");
  ::unsetenv("HUBRT_KERNEL_TIER");  // NOLINT(concurrency-mt-unsafe): single-threaded test
  EXPECT_FALSE(in_kernel_tier());
  EXPECT_FALSE(gpiosim_chip_from_env());
  EXPECT_FALSE(vcan_from_env());
}

TEST_F(KernelTierEnvironmentTest, MissingOrMalformedChipVariablesGiveNoChip) {
  set_complete_chip();
  ::unsetenv("HUBRT_GPIOSIM_SYSFS");  // NOLINT(concurrency-mt-unsafe): single-threaded test
  EXPECT_FALSE(gpiosim_chip_from_env());
  set_complete_chip();
  set("HUBRT_GPIOSIM_LINES", "16x");
  EXPECT_FALSE(gpiosim_chip_from_env());
  set("HUBRT_GPIOSIM_LINES", "0");
  EXPECT_FALSE(gpiosim_chip_from_env());
}

}  // namespace
}  // namespace hubrt::kernel_test
