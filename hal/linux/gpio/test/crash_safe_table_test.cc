// The crash-safe output table without GPIO: entries come and go, a full table says so, and the
// crash-time walk counts a descriptor the kernel refuses and leaves errno as it was. The real
// lines: crash_safe_gpiosim_test.cc in the kernel tier.
#include "crash_safe_table.h"

#include <fcntl.h>
#include <unistd.h>

#include <cerrno>
#include <vector>

#include <gtest/gtest.h>

#include "hubrt/hal/linux/crash_safe_outputs.h"

namespace hubrt::hal {
namespace {

using gpiod_detail::enter_crash_safe_output;
using gpiod_detail::leave_crash_safe_output;

class CrashSafeTable : public ::testing::Test {
 protected:
  void SetUp() override {
    fd_ = ::open("/dev/null", O_RDONLY | O_CLOEXEC);
    ASSERT_GE(fd_, 0);
    ASSERT_EQ(crash_safe_output_count(), 0U);
  }
  void TearDown() override {
    for (int slot : slots_) leave_crash_safe_output(slot);
    ::close(fd_);
  }
  int enter(bool safe, bool active_low) {
    const int slot = enter_crash_safe_output(fd_, safe, active_low);
    if (slot >= 0) slots_.push_back(slot);
    return slot;
  }

  int fd_ = -1;
  std::vector<int> slots_;
};

TEST_F(CrashSafeTable, EntriesAreCountedUntilTheyLeave) {
  const int a = enter(false, false);
  const int b = enter(true, true);
  ASSERT_GE(a, 0);
  ASSERT_GE(b, 0);
  EXPECT_NE(a, b);
  EXPECT_EQ(crash_safe_output_count(), 2U);
  leave_crash_safe_output(a);
  EXPECT_EQ(crash_safe_output_count(), 1U);
  leave_crash_safe_output(-1);  // "not entered" is ignored
  EXPECT_EQ(crash_safe_output_count(), 1U);
}

TEST_F(CrashSafeTable, AFullTableRefusesAndAFreedSlotIsReused) {
  for (std::size_t i = 0; i < kCrashSafeCapacity; ++i) ASSERT_GE(enter(false, false), 0) << i;
  EXPECT_EQ(enter_crash_safe_output(fd_, false, false), -1);
  leave_crash_safe_output(slots_.back());
  slots_.pop_back();
  EXPECT_GE(enter(false, false), 0);
}

TEST_F(CrashSafeTable, ADescriptorTheKernelRefusesIsCountedAsFailedAndErrnoIsKept) {
  enter(true, false);  // /dev/null is no GPIO line handle: the ioctl fails (ENOTTY)
  errno = EINTR;
  const CrashSafeResult result = drive_outputs_safe_from_crash();
  EXPECT_EQ(errno, EINTR) << "a signal handler must leave errno as it found it";
  EXPECT_EQ(result.driven, 0);
  EXPECT_EQ(result.failed, 1);
}

TEST_F(CrashSafeTable, NegativeOrHugeDescriptorsAreNotEntered) {
  EXPECT_EQ(enter_crash_safe_output(-1, false, false), -1);
  EXPECT_EQ(enter_crash_safe_output(1 << 25, false, false), -1);
  EXPECT_EQ(crash_safe_output_count(), 0U);
}

}  // namespace
}  // namespace hubrt::hal
