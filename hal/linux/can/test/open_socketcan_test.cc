// open_socketcan() on whatever kernel runs the test. The development machine's kernel has no
// AF_CAN: there the factory must fail at once with a message that says so. In the kernel VM
// (vcan loaded) the AF_CAN tests skip here and the contract suite covers the socket.
#include "hubrt/hal/socketcan/open_socketcan.h"

#include <unistd.h>

#include <chrono>

#include <gtest/gtest.h>
#include <linux/can.h>
#include <sys/socket.h>

namespace hubrt::hal::socketcan {
namespace {

bool kernel_has_af_can() {
  const int fd = ::socket(PF_CAN, SOCK_RAW, CAN_RAW);
  if (fd < 0) return false;
  ::close(fd);
  return true;
}

CanConfig config(std::string interface) {
  CanConfig c;
  c.bus = "tool_bus";
  c.interface = std::move(interface);
  return c;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

TEST(OpenSocketCan, KernelWithoutAfCanFailsAtOnceAndSaysWhy) {
  if (kernel_has_af_can()) GTEST_SKIP() << "this kernel has AF_CAN";
  for (const char* interface : {"can0", "vcan0"}) {
    const auto start = std::chrono::steady_clock::now();
    const auto bus = open_socketcan(config(interface));
    const auto took = std::chrono::steady_clock::now() - start;
    ASSERT_FALSE(bus.is_ok());
    EXPECT_EQ(bus.error().code, ErrorCode::kUnavailable);
    const std::string& message = bus.error().message;
    EXPECT_TRUE(contains(message, "tool_bus")) << message;
    EXPECT_TRUE(contains(message, interface)) << message;
    EXPECT_TRUE(contains(message, "no SocketCAN")) << message;
    EXPECT_TRUE(contains(message, "can_raw")) << message;
    // No retry loop, no wait: one failing socket() call. 1 s only absorbs scheduling noise.
    EXPECT_LT(took, std::chrono::seconds(1));
  }
}

TEST(OpenSocketCan, BadNamesAndFiltersAreRejectedOnAnyKernel) {
  const auto empty = open_socketcan(config(""));
  ASSERT_FALSE(empty.is_ok());
  EXPECT_EQ(empty.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(empty.error().message, "tool_bus")) << empty.error().message;

  const auto too_long = open_socketcan(config("a_very_long_ifname0"));
  ASSERT_FALSE(too_long.is_ok());
  EXPECT_EQ(too_long.error().code, ErrorCode::kInvalidArgument);

  CanConfig bad_filter = config("can0");
  bad_filter.filters.push_back(CanFilter{0x800, 0x7FF, false});
  const auto filtered = open_socketcan(bad_filter);
  ASSERT_FALSE(filtered.is_ok());
  EXPECT_EQ(filtered.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(filtered.error().message, "filter")) << filtered.error().message;
}

TEST(OpenSocketCan, MissingInterfaceIsNotFound) {
  if (!kernel_has_af_can()) GTEST_SKIP() << "needs AF_CAN (kernel tier)";
  const auto bus = open_socketcan(config("nocan7"));
  ASSERT_FALSE(bus.is_ok());
  EXPECT_EQ(bus.error().code, ErrorCode::kNotFound);
  EXPECT_TRUE(contains(bus.error().message, "nocan7")) << bus.error().message;
}

TEST(OpenSocketCan, NonCanInterfaceIsRejected) {
  if (!kernel_has_af_can()) GTEST_SKIP() << "needs AF_CAN (kernel tier)";
  const auto bus = open_socketcan(config("lo"));
  ASSERT_FALSE(bus.is_ok());
  EXPECT_EQ(bus.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(bus.error().message, "not a CAN interface")) << bus.error().message;
}

}  // namespace
}  // namespace hubrt::hal::socketcan
