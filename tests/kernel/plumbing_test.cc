// The kernel tier's plumbing, shown with the same calls the Linux HAL backends make: raw SocketCAN
// on the guest's vcan0 and libgpiod 1.6 (v1 API) on a gpio-sim chip, reached through the HUBRT_*
// environment. Every test skips outside the tier (tests/kernel/run).
#include <fcntl.h>
#include <poll.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <memory>
#include <optional>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include <gpiod.h>
#include <gtest/gtest.h>
#include <linux/can.h>
#include <linux/can/raw.h>
#include <net/if.h>
#include <sys/socket.h>

#include "hubrt/kernel_test/environment.h"
#include "hubrt/kernel_test/gpio_sim.h"
#include "hubrt/kernel_test/net_link.h"

namespace hubrt::kernel_test {
namespace {

// Generous for a frame or an edge that the kernel delivers in microseconds: the guest runs under
// software emulation (TCG) on a busy 2-core host, where a scheduling hiccup can take a second.
constexpr int kDeliveryTimeoutMs = 3000;

// errno as text (std::strerror is not thread-safe).
std::string errno_text() {
  return std::generic_category().message(errno);
}

// ---------------------------------------------------------------------------------------------
// SocketCAN

class RawCanSocket {
 public:
  // Binds a CAN_RAW socket to `ifname`; with `filter`, receives only matching identifiers.
  static std::optional<RawCanSocket> open(const std::string& ifname, std::optional<can_filter> filter = {}) {
    RawCanSocket socket(::socket(PF_CAN, SOCK_RAW | SOCK_CLOEXEC, CAN_RAW));
    if (socket.fd_ < 0) return std::nullopt;
    if (filter && ::setsockopt(socket.fd_, SOL_CAN_RAW, CAN_RAW_FILTER, &*filter, sizeof(*filter)) != 0) {
      return std::nullopt;
    }
    sockaddr_can address{};
    address.can_family = AF_CAN;
    address.can_ifindex = static_cast<int>(if_nametoindex(ifname.c_str()));
    if (address.can_ifindex == 0) return std::nullopt;
    if (::bind(socket.fd_, reinterpret_cast<const sockaddr*>(&address), sizeof(address)) != 0) {
      return std::nullopt;
    }
    return socket;
  }

  RawCanSocket(RawCanSocket&& other) noexcept : fd_(std::exchange(other.fd_, -1)) {}
  RawCanSocket& operator=(RawCanSocket&&) = delete;
  RawCanSocket(const RawCanSocket&) = delete;
  RawCanSocket& operator=(const RawCanSocket&) = delete;
  ~RawCanSocket() {
    if (fd_ >= 0) ::close(fd_);
  }

  // 0 on success, else the errno of the failed write.
  [[nodiscard]] int send(const can_frame& frame) const {
    return ::write(fd_, &frame, sizeof(frame)) == static_cast<ssize_t>(sizeof(frame)) ? 0 : errno;
  }

  // The next frame, or std::nullopt when none arrives within `timeout_ms`.
  [[nodiscard]] std::optional<can_frame> receive(int timeout_ms) const {
    pollfd waiting{fd_, POLLIN, 0};
    if (::poll(&waiting, 1, timeout_ms) != 1 || (waiting.revents & POLLIN) == 0) return std::nullopt;
    can_frame frame{};
    if (::read(fd_, &frame, sizeof(frame)) != static_cast<ssize_t>(sizeof(frame))) return std::nullopt;
    return frame;
  }

  // The socket's pending error (SO_ERROR), cleared by reading it.
  [[nodiscard]] int take_error() const {
    int error = 0;
    socklen_t size = sizeof(error);
    return ::getsockopt(fd_, SOL_SOCKET, SO_ERROR, &error, &size) == 0 ? error : errno;
  }

 private:
  explicit RawCanSocket(int fd) : fd_(fd) {}
  int fd_;
};

can_frame make_frame(canid_t id, std::vector<std::uint8_t> data) {
  can_frame frame{};
  frame.can_id = id;
  frame.len = static_cast<std::uint8_t>(data.size());
  std::memcpy(frame.data, data.data(), data.size());
  return frame;
}

class VcanTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    auto ifname = vcan_from_env();
    ASSERT_TRUE(ifname) << "HUBRT_VCAN is not set although HUBRT_KERNEL_TIER=1";
    ifname_ = *ifname;
  }
  std::string ifname_;
};

TEST_F(VcanTest, FrameSentOnOneRawSocketArrivesOnAnother) {
  auto sender = RawCanSocket::open(ifname_);
  auto receiver = RawCanSocket::open(ifname_);
  ASSERT_TRUE(sender && receiver) << "CAN_RAW on " << ifname_ << ": " << errno_text();

  ASSERT_EQ(sender->send(make_frame(0x123, {0xDE, 0xAD, 0xBE, 0xEF})), 0);
  auto frame = receiver->receive(kDeliveryTimeoutMs);
  ASSERT_TRUE(frame) << "no frame within " << kDeliveryTimeoutMs << " ms";
  EXPECT_EQ(frame->can_id, 0x123U);
  ASSERT_EQ(frame->len, 4);
  EXPECT_EQ(std::vector<std::uint8_t>(frame->data, frame->data + 4),
            (std::vector<std::uint8_t>{0xDE, 0xAD, 0xBE, 0xEF}));
}

TEST_F(VcanTest, ReceiveFilterPassesOnlyTheMatchingIdentifier) {
  auto sender = RawCanSocket::open(ifname_);
  auto receiver = RawCanSocket::open(ifname_, can_filter{0x181, CAN_SFF_MASK});
  ASSERT_TRUE(sender && receiver) << errno_text();

  ASSERT_EQ(sender->send(make_frame(0x182, {0x01})), 0);
  ASSERT_EQ(sender->send(make_frame(0x181, {0x02})), 0);
  auto frame = receiver->receive(kDeliveryTimeoutMs);
  ASSERT_TRUE(frame);
  EXPECT_EQ(frame->can_id, 0x181U) << "the filter let another identifier through first";
  EXPECT_EQ(frame->data[0], 0x02);
}

TEST_F(VcanTest, LinkDownRefusesSendsAndReportsToReceiversUntilUpAgain) {
  auto sender = RawCanSocket::open(ifname_);
  auto receiver = RawCanSocket::open(ifname_);
  ASSERT_TRUE(sender && receiver) << errno_text();

  auto down = set_link_up(ifname_, false);
  ASSERT_TRUE(down) << down.error().message;
  auto state = is_link_up(ifname_);
  ASSERT_TRUE(state) << state.error().message;
  EXPECT_FALSE(*state);
  EXPECT_EQ(sender->send(make_frame(0x10, {0x01})), ENETDOWN);
  EXPECT_EQ(receiver->take_error(), ENETDOWN) << "a bound socket is told that its interface went down";

  auto up = set_link_up(ifname_, true);
  ASSERT_TRUE(up) << up.error().message;
  ASSERT_EQ(sender->send(make_frame(0x11, {0x02})), 0);
  auto frame = receiver->receive(kDeliveryTimeoutMs);
  ASSERT_TRUE(frame) << "the same sockets work again once the link is up";
  EXPECT_EQ(frame->can_id, 0x11U);
}

// ---------------------------------------------------------------------------------------------
// GPIO: libgpiod 1.6 on gpio-sim

struct ChipCloser {
  void operator()(gpiod_chip* chip) const { gpiod_chip_close(chip); }
};
using ChipHandle = std::unique_ptr<gpiod_chip, ChipCloser>;

class GpioSimTest : public ::testing::Test {
 protected:
  void SetUp() override {
    HUBRT_SKIP_OUTSIDE_KERNEL_TIER();
    auto sim = gpiosim_chip_from_env();
    ASSERT_TRUE(sim) << "HUBRT_GPIOSIM_* incomplete although HUBRT_KERNEL_TIER=1";
    sim_ = *sim;
    chip_.reset(gpiod_chip_open_by_name(sim_.name.c_str()));
    ASSERT_NE(chip_, nullptr) << "gpiod_chip_open_by_name(" << sim_.name << "): " << errno_text();
  }

  gpiod_line* line(unsigned offset) { return gpiod_chip_get_line(chip_.get(), offset); }

  GpioSimChip sim_;
  ChipHandle chip_;
};

TEST_F(GpioSimTest, ChipOpensByNameDevicePathAndLabelWithTheAdvertisedLines) {
  EXPECT_EQ(gpiod_chip_num_lines(chip_.get()), sim_.num_lines);
  EXPECT_STREQ(gpiod_chip_label(chip_.get()), sim_.label.c_str());
  ChipHandle by_path(gpiod_chip_open(sim_.dev_path.c_str()));
  ASSERT_NE(by_path, nullptr) << sim_.dev_path << ": " << errno_text();
  EXPECT_STREQ(gpiod_chip_name(by_path.get()), sim_.name.c_str());
  ChipHandle by_label(gpiod_chip_open_by_label(sim_.label.c_str()));
  ASSERT_NE(by_label, nullptr) << "label " << sim_.label;
  EXPECT_STREQ(gpiod_chip_name(by_label.get()), sim_.name.c_str());
}

TEST_F(GpioSimTest, OutputSetThroughLibgpiodIsWhatTheSimulatorSees) {
  gpiod_line* output = line(0);
  ASSERT_NE(output, nullptr);
  ASSERT_EQ(gpiod_line_request_output(output, "hubrt-kernel-test", 1), 0) << errno_text();
  auto high = read_value(sim_, 0);
  ASSERT_TRUE(high) << high.error().message;
  EXPECT_EQ(*high, 1);
  ASSERT_EQ(gpiod_line_set_value(output, 0), 0);
  auto low = read_value(sim_, 0);
  ASSERT_TRUE(low) << low.error().message;
  EXPECT_EQ(*low, 0);
}

TEST_F(GpioSimTest, InputReadThroughLibgpiodFollowsTheSimulatorPull) {
  gpiod_line* input = line(1);
  ASSERT_NE(input, nullptr);
  ASSERT_EQ(gpiod_line_request_input(input, "hubrt-kernel-test"), 0) << errno_text();
  ASSERT_TRUE(set_pull(sim_, 1, Pull::kUp));
  EXPECT_EQ(gpiod_line_get_value(input), 1);
  ASSERT_TRUE(set_pull(sim_, 1, Pull::kDown));
  EXPECT_EQ(gpiod_line_get_value(input), 0);
}

TEST_F(GpioSimTest, SimulatorPullRaisesRisingAndFallingEdgeEvents) {
  gpiod_line* input = line(2);
  ASSERT_NE(input, nullptr);
  ASSERT_EQ(gpiod_line_request_both_edges_events(input, "hubrt-kernel-test"), 0) << errno_text();
  const timespec timeout{kDeliveryTimeoutMs / 1000, 0};
  gpiod_line_event event{};

  ASSERT_TRUE(set_pull(sim_, 2, Pull::kUp));
  ASSERT_EQ(gpiod_line_event_wait(input, &timeout), 1) << "no edge within " << kDeliveryTimeoutMs << " ms";
  ASSERT_EQ(gpiod_line_event_read(input, &event), 0);
  EXPECT_EQ(event.event_type, GPIOD_LINE_EVENT_RISING_EDGE);

  ASSERT_TRUE(set_pull(sim_, 2, Pull::kDown));
  ASSERT_EQ(gpiod_line_event_wait(input, &timeout), 1);
  ASSERT_EQ(gpiod_line_event_read(input, &event), 0);
  EXPECT_EQ(event.event_type, GPIOD_LINE_EVENT_FALLING_EDGE);
}

TEST_F(GpioSimTest, LineHeldByOneConsumerIsBusyForAnother) {
  ASSERT_EQ(gpiod_line_request_output(line(3), "first-owner", 0), 0) << errno_text();
  ChipHandle second(gpiod_chip_open(sim_.dev_path.c_str()));
  ASSERT_NE(second, nullptr);
  EXPECT_EQ(gpiod_line_request_input(gpiod_chip_get_line(second.get(), 3), "second-owner"), -1);
  EXPECT_EQ(errno, EBUSY);
}

TEST_F(GpioSimTest, ExtraChipWithNamedLinesIsFoundByLineName) {
  auto extra = ScopedGpioSimChip::create("hubrt-kt-named", 4, {{2, "dock_closed"}});
  ASSERT_TRUE(extra) << extra.error().message;
  EXPECT_EQ(extra->chip().num_lines, 4U);
  {
    ChipHandle chip(gpiod_chip_open(extra->chip().dev_path.c_str()));
    ASSERT_NE(chip, nullptr) << extra->chip().dev_path;
    EXPECT_EQ(gpiod_chip_find_line(chip.get(), "dock_closed"), gpiod_chip_get_line(chip.get(), 2));
    EXPECT_EQ(gpiod_chip_find_line(chip.get(), "no_such_line"), nullptr);
  }  // lines released before the chip is removed
}

// Shows what a failing kernel-tier run looks like (tests/kernel/run --demo-failure). Skipped
// unless asked for, so it never fails the suite.
TEST_F(GpioSimTest, DeliberateFailureOnlyWhenAskedFor) {
  const char* demo = std::getenv("HUBRT_KERNEL_DEMO_FAILURE");  // NOLINT(concurrency-mt-unsafe)
  if (demo == nullptr || std::string(demo) != "1") GTEST_SKIP() << "set HUBRT_KERNEL_DEMO_FAILURE=1 to run";
  ASSERT_EQ(gpiod_line_request_output(line(0), "hubrt-kernel-test", 1), 0);
  auto value = read_value(sim_, 0);
  ASSERT_TRUE(value) << value.error().message;
  EXPECT_EQ(*value, 0) << "deliberate failure (--demo-failure): line 0 is driven high, this expects low";
}

}  // namespace
}  // namespace hubrt::kernel_test
